; multi-goal 22: Active_HallLight & RobotNear_BrightTable5 & On_VacuumCup_Table3
(define (problem btpg-rw-multi-022)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (active halllight) (robotnear brighttable5) (on vacuumcup table3)))
  (:metric minimize (total-cost)))
