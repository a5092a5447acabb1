; multi-goal 16: RobotNear_Table1 & On_SpringWater_Table2
(define (problem btpg-rw-multi-016)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (robotnear table1) (on springwater table2)))
  (:metric minimize (total-cost)))
