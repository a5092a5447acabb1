; multi-goal 14: On_VacuumCup_Table3 & Holding_Coffee
(define (problem btpg-rw-multi-014)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (on vacuumcup table3) (holding coffee)))
  (:metric minimize (total-cost)))
