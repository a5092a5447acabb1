; multi-goal 39: On_Coffee_Table2 & Holding_Bernachon & RobotNear_QuietTable2
(define (problem btpg-rw-multi-039)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (on coffee table2) (holding bernachon) (robotnear quiettable2)))
  (:metric minimize (total-cost)))
