; multi-goal 2: On_Water_BrightTable6 & Holding_ADMilk
(define (problem btpg-rw-multi-002)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (on water brighttable6) (holding admilk)))
  (:metric minimize (total-cost)))
