; multi-goal 21: On_Milk_BrightTable6 & Holding_Bernachon & RobotNear_CoffeeStation
(define (problem btpg-rw-multi-021)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (on milk brighttable6) (holding bernachon) (robotnear coffeestation)))
  (:metric minimize (total-cost)))
