; multi-goal 5: On_MilkDrink_CoffeeStation & On_Bernachon_Bar
(define (problem btpg-rw-multi-005)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (on milkdrink coffeestation) (on bernachon bar)))
  (:metric minimize (total-cost)))
