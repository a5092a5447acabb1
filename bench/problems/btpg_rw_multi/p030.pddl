; multi-goal 30: Active_TubeLight & RobotNear_BrightTable5 & Holding_NFCJuice
(define (problem btpg-rw-multi-030)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (active tubelight) (robotnear brighttable5) (holding nfcjuice)))
  (:metric minimize (total-cost)))
