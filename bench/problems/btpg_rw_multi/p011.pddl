; multi-goal 11: Active_HallLight & On_Milk_BrightTable6
(define (problem btpg-rw-multi-011)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (active halllight) (on milk brighttable6)))
  (:metric minimize (total-cost)))
