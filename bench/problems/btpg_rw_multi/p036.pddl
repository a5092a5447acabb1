; multi-goal 36: RobotNear_BrightTable5 & On_ADMilk_Bar2 & On_Milk_CoffeeStation
(define (problem btpg-rw-multi-036)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (robotnear brighttable5) (on admilk bar2) (on milk coffeestation)))
  (:metric minimize (total-cost)))
