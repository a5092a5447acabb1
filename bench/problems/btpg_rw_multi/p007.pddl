; multi-goal 7: IsClean_Floor & RobotNear_CoffeeStation
(define (problem btpg-rw-multi-007)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (isclean floor) (robotnear coffeestation)))
  (:metric minimize (total-cost)))
