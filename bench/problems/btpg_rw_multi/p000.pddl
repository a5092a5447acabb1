; multi-goal 0: On_Coffee_WaterStation & On_MilkDrink_BrightTable6
(define (problem btpg-rw-multi-000)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (on coffee waterstation) (on milkdrink brighttable6)))
  (:metric minimize (total-cost)))
