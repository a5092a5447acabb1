; multi-goal 1: Exists_Water & IsClean_Table1
(define (problem btpg-rw-multi-001)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (exists_ water) (isclean table1)))
  (:metric minimize (total-cost)))
