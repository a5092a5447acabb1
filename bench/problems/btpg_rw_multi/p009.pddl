; multi-goal 9: IsClean_Chairs & Holding_Milk
(define (problem btpg-rw-multi-009)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (isclean chairs) (holding milk)))
  (:metric minimize (total-cost)))
