; multi-goal 34: Exists_Water & Exists_Dessert & IsClean_Chairs
(define (problem btpg-rw-multi-034)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (exists_ water) (exists_ dessert) (isclean chairs)))
  (:metric minimize (total-cost)))
