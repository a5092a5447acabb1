; multi-goal 31: Exists_Water & Active_TubeLight & RobotNear_Table2
(define (problem btpg-rw-multi-031)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (exists_ water) (active tubelight) (robotnear table2)))
  (:metric minimize (total-cost)))
