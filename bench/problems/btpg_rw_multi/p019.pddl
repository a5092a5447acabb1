; multi-goal 19: Low_ACTemperature & Exists_Dessert
(define (problem btpg-rw-multi-019)
  (:domain btpg-rw)
  (:init (exists_ admilk) (exists_ bernachon) (exists_ bottleddrink) (exists_ chips) (exists_ milk) (exists_ milkdrink) (exists_ nfcjuice) (exists_ softdrink) (exists_ springwater) (exists_ vacuumcup) (exists_ yogurt) (holding nothing) (robotnear bar) (= (total-cost) 0))
  (:goal (and (low actemperature) (exists_ dessert)))
  (:metric minimize (total-cost)))
