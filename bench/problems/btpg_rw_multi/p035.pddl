; multi-goal 35: Holding_ADMilk & On_Milk_CoffeeStation & On_Yogurt_WaterStation
(define (problem btpg-rw-multi-035)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (holding admilk) (on milk coffeestation) (on yogurt waterstation)))
  (:metric minimize (total-cost)))
