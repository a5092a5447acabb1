; multi-goal 33: Active_HallLight & Exists_Dessert & On_MilkDrink_CoffeeStation
(define (problem btpg-rw-multi-033)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (active halllight) (exists_ dessert) (on milkdrink coffeestation)))
  (:metric minimize (total-cost)))
