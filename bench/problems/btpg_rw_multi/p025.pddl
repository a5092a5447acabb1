; multi-goal 25: Holding_NFCJuice & On_Water_BrightTable6 & On_Softdrink_CoffeeStation
(define (problem btpg-rw-multi-025)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (holding nfcjuice) (on water brighttable6) (on softdrink coffeestation)))
  (:metric minimize (total-cost)))
