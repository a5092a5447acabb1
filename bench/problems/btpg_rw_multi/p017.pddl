; multi-goal 17: IsClean_Table1 & On_Milk_CoffeeStation
(define (problem btpg-rw-multi-017)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (isclean table1) (on milk coffeestation)))
  (:metric minimize (total-cost)))
