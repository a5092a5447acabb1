; multi-goal 6: On_MilkDrink_CoffeeStation & Holding_NFCJuice
(define (problem btpg-rw-multi-006)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (on milkdrink coffeestation) (holding nfcjuice)))
  (:metric minimize (total-cost)))
