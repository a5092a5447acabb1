; multi-goal 29: On_VacuumCup_Table3 & On_Coffee_WaterStation & RobotNear_QuietTable1
(define (problem btpg-rw-multi-029)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (on vacuumcup table3) (on coffee waterstation) (robotnear quiettable1)))
  (:metric minimize (total-cost)))
