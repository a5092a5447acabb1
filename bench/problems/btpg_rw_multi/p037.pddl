; multi-goal 37: Holding_Softdrink & On_MilkDrink_BrightTable6 & On_VacuumCup_WaterStation
(define (problem btpg-rw-multi-037)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (holding softdrink) (on milkdrink brighttable6) (on vacuumcup waterstation)))
  (:metric minimize (total-cost)))
