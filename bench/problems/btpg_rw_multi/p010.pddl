; multi-goal 10: IsClean_Floor & On_Water_BrightTable6
(define (problem btpg-rw-multi-010)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (isclean floor) (on water brighttable6)))
  (:metric minimize (total-cost)))
