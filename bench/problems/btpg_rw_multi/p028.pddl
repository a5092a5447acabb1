; multi-goal 28: Exists_Dessert & RobotNear_Table1 & Holding_Milk
(define (problem btpg-rw-multi-028)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (exists_ dessert) (robotnear table1) (holding milk)))
  (:metric minimize (total-cost)))
