; multi-goal 24: Exists_Dessert & On_VacuumCup_Table3 & RobotNear_Table1
(define (problem btpg-rw-multi-024)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (exists_ dessert) (on vacuumcup table3) (robotnear table1)))
  (:metric minimize (total-cost)))
