; multi-goal 8: IsClean_Table1 & On_Yogurt_WaterStation
(define (problem btpg-rw-multi-008)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (isclean table1) (on yogurt waterstation)))
  (:metric minimize (total-cost)))
