; multi-goal 18: Holding_Yogurt & On_Softdrink_CoffeeStation
(define (problem btpg-rw-multi-018)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (holding yogurt) (on softdrink coffeestation)))
  (:metric minimize (total-cost)))
