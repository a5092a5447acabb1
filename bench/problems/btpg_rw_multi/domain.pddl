; BTPG scene RW (RoboWaiter): every grounded action of BTPG as one parameterless action, same pre, add, del and cost
(define (domain btpg-rw)
  (:requirements :strips :action-costs)
  (:constants ac actemperature admilk bar bar2 bernachon bottleddrink brighttable1 brighttable2 brighttable3 brighttable4 brighttable5 brighttable6 chairs chips coffee coffeestation coffeetable curtain dessert floor halllight milk milkdrink nfcjuice nothing quiettable1 quiettable2 softdrink springwater table1 table2 table3 tubelight vacuumcup water waterstation watertable yogurt)
  (:predicates
  (active ?x0)
  (closed ?x0)
  (exists_ ?x0)
  (holding ?x0)
  (isclean ?x0)
  (low ?x0)
  (on ?x0 ?x1)
  (robotnear ?x0))
  (:functions (total-cost) - number)
  (:action turn_ac_on
   :parameters ()
   :precondition (and (holding nothing))
   :effect (and (active ac) (increase (total-cost) 3)))
  (:action turn_ac_off
   :parameters ()
   :precondition (and (active ac) (holding nothing))
   :effect (and (not (active ac)) (increase (total-cost) 3)))
  (:action turn_tubelight_on
   :parameters ()
   :precondition (and (holding nothing))
   :effect (and (active tubelight) (increase (total-cost) 3)))
  (:action turn_tubelight_off
   :parameters ()
   :precondition (and (active tubelight) (holding nothing))
   :effect (and (not (active tubelight)) (increase (total-cost) 3)))
  (:action turn_halllight_on
   :parameters ()
   :precondition (and (holding nothing))
   :effect (and (active halllight) (increase (total-cost) 3)))
  (:action turn_halllight_off
   :parameters ()
   :precondition (and (active halllight) (holding nothing))
   :effect (and (not (active halllight)) (increase (total-cost) 3)))
  (:action turn_curtain_on
   :parameters ()
   :precondition (and (closed curtain))
   :effect (and (not (closed curtain)) (increase (total-cost) 3)))
  (:action turn_curtain_off
   :parameters ()
   :precondition (and )
   :effect (and (closed curtain) (increase (total-cost) 3)))
  (:action turn_actemperature_up
   :parameters ()
   :precondition (and (active ac) (holding nothing))
   :effect (and (not (low actemperature)) (increase (total-cost) 3)))
  (:action turn_actemperature_down
   :parameters ()
   :precondition (and (active ac) (holding nothing))
   :effect (and (low actemperature) (increase (total-cost) 3)))
  (:action putdown_chips_bar
   :parameters ()
   :precondition (and (holding chips) (robotnear bar))
   :effect (and (on chips bar) (not (holding chips)) (increase (total-cost) 20)))
  (:action putdown_bottleddrink_bar
   :parameters ()
   :precondition (and (holding bottleddrink) (robotnear bar))
   :effect (and (on bottleddrink bar) (not (holding bottleddrink)) (increase (total-cost) 20)))
  (:action putdown_admilk_bar2
   :parameters ()
   :precondition (and (holding admilk) (robotnear bar2))
   :effect (and (on admilk bar2) (not (holding admilk)) (increase (total-cost) 20)))
  (:action putdown_vacuumcup_bar2
   :parameters ()
   :precondition (and (holding vacuumcup) (robotnear bar2))
   :effect (and (on vacuumcup bar2) (not (holding vacuumcup)) (increase (total-cost) 20)))
  (:action putdown_water_table2
   :parameters ()
   :precondition (and (holding water) (robotnear table2))
   :effect (and (on water table2) (not (holding water)) (increase (total-cost) 20)))
  (:action putdown_nfcjuice_table2
   :parameters ()
   :precondition (and (holding nfcjuice) (robotnear table2))
   :effect (and (on nfcjuice table2) (not (holding nfcjuice)) (increase (total-cost) 20)))
  (:action putdown_admilk_waterstation
   :parameters ()
   :precondition (and (holding admilk) (robotnear waterstation))
   :effect (and (on admilk waterstation) (not (holding admilk)) (increase (total-cost) 20)))
  (:action putdown_vacuumcup_waterstation
   :parameters ()
   :precondition (and (holding vacuumcup) (robotnear waterstation))
   :effect (and (on vacuumcup waterstation) (not (holding vacuumcup)) (increase (total-cost) 20)))
  (:action putdown_softdrink_table1
   :parameters ()
   :precondition (and (holding softdrink) (robotnear table1))
   :effect (and (on softdrink table1) (not (holding softdrink)) (increase (total-cost) 20)))
  (:action putdown_milkdrink_bar
   :parameters ()
   :precondition (and (holding milkdrink) (robotnear bar))
   :effect (and (on milkdrink bar) (not (holding milkdrink)) (increase (total-cost) 20)))
  (:action putdown_yogurt_table2
   :parameters ()
   :precondition (and (holding yogurt) (robotnear table2))
   :effect (and (on yogurt table2) (not (holding yogurt)) (increase (total-cost) 20)))
  (:action putdown_water_bar2
   :parameters ()
   :precondition (and (holding water) (robotnear bar2))
   :effect (and (on water bar2) (not (holding water)) (increase (total-cost) 20)))
  (:action putdown_coffee_bar
   :parameters ()
   :precondition (and (holding coffee) (robotnear bar))
   :effect (and (on coffee bar) (not (holding coffee)) (increase (total-cost) 20)))
  (:action putdown_softdrink_coffeestation
   :parameters ()
   :precondition (and (holding softdrink) (robotnear coffeestation))
   :effect (and (on softdrink coffeestation) (not (holding softdrink)) (increase (total-cost) 20)))
  (:action putdown_nfcjuice_bar2
   :parameters ()
   :precondition (and (holding nfcjuice) (robotnear bar2))
   :effect (and (on nfcjuice bar2) (not (holding nfcjuice)) (increase (total-cost) 20)))
  (:action putdown_springwater_table2
   :parameters ()
   :precondition (and (holding springwater) (robotnear table2))
   :effect (and (on springwater table2) (not (holding springwater)) (increase (total-cost) 20)))
  (:action putdown_milkdrink_coffeestation
   :parameters ()
   :precondition (and (holding milkdrink) (robotnear coffeestation))
   :effect (and (on milkdrink coffeestation) (not (holding milkdrink)) (increase (total-cost) 20)))
  (:action putdown_admilk_table1
   :parameters ()
   :precondition (and (holding admilk) (robotnear table1))
   :effect (and (on admilk table1) (not (holding admilk)) (increase (total-cost) 20)))
  (:action putdown_water_waterstation
   :parameters ()
   :precondition (and (holding water) (robotnear waterstation))
   :effect (and (on water waterstation) (not (holding water)) (increase (total-cost) 20)))
  (:action putdown_vacuumcup_table1
   :parameters ()
   :precondition (and (holding vacuumcup) (robotnear table1))
   :effect (and (on vacuumcup table1) (not (holding vacuumcup)) (increase (total-cost) 20)))
  (:action putdown_nfcjuice_waterstation
   :parameters ()
   :precondition (and (holding nfcjuice) (robotnear waterstation))
   :effect (and (on nfcjuice waterstation) (not (holding nfcjuice)) (increase (total-cost) 20)))
  (:action putdown_softdrink_table3
   :parameters ()
   :precondition (and (holding softdrink) (robotnear table3))
   :effect (and (on softdrink table3) (not (holding softdrink)) (increase (total-cost) 20)))
  (:action putdown_yogurt_waterstation
   :parameters ()
   :precondition (and (holding yogurt) (robotnear waterstation))
   :effect (and (on yogurt waterstation) (not (holding yogurt)) (increase (total-cost) 20)))
  (:action putdown_milk_table2
   :parameters ()
   :precondition (and (holding milk) (robotnear table2))
   :effect (and (on milk table2) (not (holding milk)) (increase (total-cost) 20)))
  (:action putdown_dessert_coffeestation
   :parameters ()
   :precondition (and (holding dessert) (robotnear coffeestation))
   :effect (and (on dessert coffeestation) (not (holding dessert)) (increase (total-cost) 20)))
  (:action putdown_water_table1
   :parameters ()
   :precondition (and (holding water) (robotnear table1))
   :effect (and (on water table1) (not (holding water)) (increase (total-cost) 20)))
  (:action putdown_admilk_table3
   :parameters ()
   :precondition (and (holding admilk) (robotnear table3))
   :effect (and (on admilk table3) (not (holding admilk)) (increase (total-cost) 20)))
  (:action putdown_chips_table2
   :parameters ()
   :precondition (and (holding chips) (robotnear table2))
   :effect (and (on chips table2) (not (holding chips)) (increase (total-cost) 20)))
  (:action putdown_bottleddrink_table2
   :parameters ()
   :precondition (and (holding bottleddrink) (robotnear table2))
   :effect (and (on bottleddrink table2) (not (holding bottleddrink)) (increase (total-cost) 20)))
  (:action putdown_yogurt_brighttable6
   :parameters ()
   :precondition (and (holding yogurt) (robotnear brighttable6))
   :effect (and (on yogurt brighttable6) (not (holding yogurt)) (increase (total-cost) 20)))
  (:action putdown_vacuumcup_table3
   :parameters ()
   :precondition (and (holding vacuumcup) (robotnear table3))
   :effect (and (on vacuumcup table3) (not (holding vacuumcup)) (increase (total-cost) 20)))
  (:action putdown_springwater_waterstation
   :parameters ()
   :precondition (and (holding springwater) (robotnear waterstation))
   :effect (and (on springwater waterstation) (not (holding springwater)) (increase (total-cost) 20)))
  (:action putdown_nfcjuice_table1
   :parameters ()
   :precondition (and (holding nfcjuice) (robotnear table1))
   :effect (and (on nfcjuice table1) (not (holding nfcjuice)) (increase (total-cost) 20)))
  (:action putdown_springwater_brighttable6
   :parameters ()
   :precondition (and (holding springwater) (robotnear brighttable6))
   :effect (and (on springwater brighttable6) (not (holding springwater)) (increase (total-cost) 20)))
  (:action putdown_dessert_table3
   :parameters ()
   :precondition (and (holding dessert) (robotnear table3))
   :effect (and (on dessert table3) (not (holding dessert)) (increase (total-cost) 20)))
  (:action putdown_softdrink_bar
   :parameters ()
   :precondition (and (holding softdrink) (robotnear bar))
   :effect (and (on softdrink bar) (not (holding softdrink)) (increase (total-cost) 20)))
  (:action putdown_milk_waterstation
   :parameters ()
   :precondition (and (holding milk) (robotnear waterstation))
   :effect (and (on milk waterstation) (not (holding milk)) (increase (total-cost) 20)))
  (:action putdown_bernachon_waterstation
   :parameters ()
   :precondition (and (holding bernachon) (robotnear waterstation))
   :effect (and (on bernachon waterstation) (not (holding bernachon)) (increase (total-cost) 20)))
  (:action putdown_water_table3
   :parameters ()
   :precondition (and (holding water) (robotnear table3))
   :effect (and (on water table3) (not (holding water)) (increase (total-cost) 20)))
  (:action putdown_chips_waterstation
   :parameters ()
   :precondition (and (holding chips) (robotnear waterstation))
   :effect (and (on chips waterstation) (not (holding chips)) (increase (total-cost) 20)))
  (:action putdown_bottleddrink_waterstation
   :parameters ()
   :precondition (and (holding bottleddrink) (robotnear waterstation))
   :effect (and (on bottleddrink waterstation) (not (holding bottleddrink)) (increase (total-cost) 20)))
  (:action putdown_milk_brighttable6
   :parameters ()
   :precondition (and (holding milk) (robotnear brighttable6))
   :effect (and (on milk brighttable6) (not (holding milk)) (increase (total-cost) 20)))
  (:action putdown_bernachon_brighttable6
   :parameters ()
   :precondition (and (holding bernachon) (robotnear brighttable6))
   :effect (and (on bernachon brighttable6) (not (holding bernachon)) (increase (total-cost) 20)))
  (:action putdown_coffee_table2
   :parameters ()
   :precondition (and (holding coffee) (robotnear table2))
   :effect (and (on coffee table2) (not (holding coffee)) (increase (total-cost) 20)))
  (:action putdown_chips_brighttable6
   :parameters ()
   :precondition (and (holding chips) (robotnear brighttable6))
   :effect (and (on chips brighttable6) (not (holding chips)) (increase (total-cost) 20)))
  (:action putdown_bottleddrink_brighttable6
   :parameters ()
   :precondition (and (holding bottleddrink) (robotnear brighttable6))
   :effect (and (on bottleddrink brighttable6) (not (holding bottleddrink)) (increase (total-cost) 20)))
  (:action putdown_admilk_bar
   :parameters ()
   :precondition (and (holding admilk) (robotnear bar))
   :effect (and (on admilk bar) (not (holding admilk)) (increase (total-cost) 20)))
  (:action putdown_dessert_bar
   :parameters ()
   :precondition (and (holding dessert) (robotnear bar))
   :effect (and (on dessert bar) (not (holding dessert)) (increase (total-cost) 20)))
  (:action putdown_yogurt_bar2
   :parameters ()
   :precondition (and (holding yogurt) (robotnear bar2))
   :effect (and (on yogurt bar2) (not (holding yogurt)) (increase (total-cost) 20)))
  (:action putdown_admilk_coffeestation
   :parameters ()
   :precondition (and (holding admilk) (robotnear coffeestation))
   :effect (and (on admilk coffeestation) (not (holding admilk)) (increase (total-cost) 20)))
  (:action putdown_vacuumcup_coffeestation
   :parameters ()
   :precondition (and (holding vacuumcup) (robotnear coffeestation))
   :effect (and (on vacuumcup coffeestation) (not (holding vacuumcup)) (increase (total-cost) 20)))
  (:action putdown_springwater_bar2
   :parameters ()
   :precondition (and (holding springwater) (robotnear bar2))
   :effect (and (on springwater bar2) (not (holding springwater)) (increase (total-cost) 20)))
  (:action putdown_bernachon_table2
   :parameters ()
   :precondition (and (holding bernachon) (robotnear table2))
   :effect (and (on bernachon table2) (not (holding bernachon)) (increase (total-cost) 20)))
  (:action putdown_coffee_waterstation
   :parameters ()
   :precondition (and (holding coffee) (robotnear waterstation))
   :effect (and (on coffee waterstation) (not (holding coffee)) (increase (total-cost) 20)))
  (:action putdown_milkdrink_brighttable6
   :parameters ()
   :precondition (and (holding milkdrink) (robotnear brighttable6))
   :effect (and (on milkdrink brighttable6) (not (holding milkdrink)) (increase (total-cost) 20)))
  (:action putdown_coffee_brighttable6
   :parameters ()
   :precondition (and (holding coffee) (robotnear brighttable6))
   :effect (and (on coffee brighttable6) (not (holding coffee)) (increase (total-cost) 20)))
  (:action putdown_water_coffeestation
   :parameters ()
   :precondition (and (holding water) (robotnear coffeestation))
   :effect (and (on water coffeestation) (not (holding water)) (increase (total-cost) 20)))
  (:action putdown_milk_bar2
   :parameters ()
   :precondition (and (holding milk) (robotnear bar2))
   :effect (and (on milk bar2) (not (holding milk)) (increase (total-cost) 20)))
  (:action putdown_nfcjuice_coffeestation
   :parameters ()
   :precondition (and (holding nfcjuice) (robotnear coffeestation))
   :effect (and (on nfcjuice coffeestation) (not (holding nfcjuice)) (increase (total-cost) 20)))
  (:action putdown_bernachon_bar2
   :parameters ()
   :precondition (and (holding bernachon) (robotnear bar2))
   :effect (and (on bernachon bar2) (not (holding bernachon)) (increase (total-cost) 20)))
  (:action putdown_yogurt_table1
   :parameters ()
   :precondition (and (holding yogurt) (robotnear table1))
   :effect (and (on yogurt table1) (not (holding yogurt)) (increase (total-cost) 20)))
  (:action putdown_dessert_brighttable6
   :parameters ()
   :precondition (and (holding dessert) (robotnear brighttable6))
   :effect (and (on dessert brighttable6) (not (holding dessert)) (increase (total-cost) 20)))
  (:action putdown_chips_bar2
   :parameters ()
   :precondition (and (holding chips) (robotnear bar2))
   :effect (and (on chips bar2) (not (holding chips)) (increase (total-cost) 20)))
  (:action putdown_bottleddrink_bar2
   :parameters ()
   :precondition (and (holding bottleddrink) (robotnear bar2))
   :effect (and (on bottleddrink bar2) (not (holding bottleddrink)) (increase (total-cost) 20)))
  (:action putdown_springwater_table1
   :parameters ()
   :precondition (and (holding springwater) (robotnear table1))
   :effect (and (on springwater table1) (not (holding springwater)) (increase (total-cost) 20)))
  (:action putdown_yogurt_coffeestation
   :parameters ()
   :precondition (and (holding yogurt) (robotnear coffeestation))
   :effect (and (on yogurt coffeestation) (not (holding yogurt)) (increase (total-cost) 20)))
  (:action putdown_nfcjuice_table3
   :parameters ()
   :precondition (and (holding nfcjuice) (robotnear table3))
   :effect (and (on nfcjuice table3) (not (holding nfcjuice)) (increase (total-cost) 20)))
  (:action putdown_milkdrink_table2
   :parameters ()
   :precondition (and (holding milkdrink) (robotnear table2))
   :effect (and (on milkdrink table2) (not (holding milkdrink)) (increase (total-cost) 20)))
  (:action putdown_springwater_coffeestation
   :parameters ()
   :precondition (and (holding springwater) (robotnear coffeestation))
   :effect (and (on springwater coffeestation) (not (holding springwater)) (increase (total-cost) 20)))
  (:action putdown_vacuumcup_bar
   :parameters ()
   :precondition (and (holding vacuumcup) (robotnear bar))
   :effect (and (on vacuumcup bar) (not (holding vacuumcup)) (increase (total-cost) 20)))
  (:action putdown_yogurt_table3
   :parameters ()
   :precondition (and (holding yogurt) (robotnear table3))
   :effect (and (on yogurt table3) (not (holding yogurt)) (increase (total-cost) 20)))
  (:action putdown_milk_table1
   :parameters ()
   :precondition (and (holding milk) (robotnear table1))
   :effect (and (on milk table1) (not (holding milk)) (increase (total-cost) 20)))
  (:action putdown_milkdrink_bar2
   :parameters ()
   :precondition (and (holding milkdrink) (robotnear bar2))
   :effect (and (on milkdrink bar2) (not (holding milkdrink)) (increase (total-cost) 20)))
  (:action putdown_bernachon_table1
   :parameters ()
   :precondition (and (holding bernachon) (robotnear table1))
   :effect (and (on bernachon table1) (not (holding bernachon)) (increase (total-cost) 20)))
  (:action putdown_dessert_table2
   :parameters ()
   :precondition (and (holding dessert) (robotnear table2))
   :effect (and (on dessert table2) (not (holding dessert)) (increase (total-cost) 20)))
  (:action putdown_springwater_table3
   :parameters ()
   :precondition (and (holding springwater) (robotnear table3))
   :effect (and (on springwater table3) (not (holding springwater)) (increase (total-cost) 20)))
  (:action putdown_softdrink_waterstation
   :parameters ()
   :precondition (and (holding softdrink) (robotnear waterstation))
   :effect (and (on softdrink waterstation) (not (holding softdrink)) (increase (total-cost) 20)))
  (:action putdown_coffee_bar2
   :parameters ()
   :precondition (and (holding coffee) (robotnear bar2))
   :effect (and (on coffee bar2) (not (holding coffee)) (increase (total-cost) 20)))
  (:action putdown_chips_table1
   :parameters ()
   :precondition (and (holding chips) (robotnear table1))
   :effect (and (on chips table1) (not (holding chips)) (increase (total-cost) 20)))
  (:action putdown_bottleddrink_table1
   :parameters ()
   :precondition (and (holding bottleddrink) (robotnear table1))
   :effect (and (on bottleddrink table1) (not (holding bottleddrink)) (increase (total-cost) 20)))
  (:action putdown_milk_coffeestation
   :parameters ()
   :precondition (and (holding milk) (robotnear coffeestation))
   :effect (and (on milk coffeestation) (not (holding milk)) (increase (total-cost) 20)))
  (:action putdown_bernachon_coffeestation
   :parameters ()
   :precondition (and (holding bernachon) (robotnear coffeestation))
   :effect (and (on bernachon coffeestation) (not (holding bernachon)) (increase (total-cost) 20)))
  (:action putdown_milkdrink_waterstation
   :parameters ()
   :precondition (and (holding milkdrink) (robotnear waterstation))
   :effect (and (on milkdrink waterstation) (not (holding milkdrink)) (increase (total-cost) 20)))
  (:action putdown_softdrink_brighttable6
   :parameters ()
   :precondition (and (holding softdrink) (robotnear brighttable6))
   :effect (and (on softdrink brighttable6) (not (holding softdrink)) (increase (total-cost) 20)))
  (:action putdown_water_bar
   :parameters ()
   :precondition (and (holding water) (robotnear bar))
   :effect (and (on water bar) (not (holding water)) (increase (total-cost) 20)))
  (:action putdown_chips_coffeestation
   :parameters ()
   :precondition (and (holding chips) (robotnear coffeestation))
   :effect (and (on chips coffeestation) (not (holding chips)) (increase (total-cost) 20)))
  (:action putdown_bottleddrink_coffeestation
   :parameters ()
   :precondition (and (holding bottleddrink) (robotnear coffeestation))
   :effect (and (on bottleddrink coffeestation) (not (holding bottleddrink)) (increase (total-cost) 20)))
  (:action putdown_nfcjuice_bar
   :parameters ()
   :precondition (and (holding nfcjuice) (robotnear bar))
   :effect (and (on nfcjuice bar) (not (holding nfcjuice)) (increase (total-cost) 20)))
  (:action putdown_dessert_bar2
   :parameters ()
   :precondition (and (holding dessert) (robotnear bar2))
   :effect (and (on dessert bar2) (not (holding dessert)) (increase (total-cost) 20)))
  (:action putdown_milk_table3
   :parameters ()
   :precondition (and (holding milk) (robotnear table3))
   :effect (and (on milk table3) (not (holding milk)) (increase (total-cost) 20)))
  (:action putdown_bernachon_table3
   :parameters ()
   :precondition (and (holding bernachon) (robotnear table3))
   :effect (and (on bernachon table3) (not (holding bernachon)) (increase (total-cost) 20)))
  (:action putdown_admilk_brighttable6
   :parameters ()
   :precondition (and (holding admilk) (robotnear brighttable6))
   :effect (and (on admilk brighttable6) (not (holding admilk)) (increase (total-cost) 20)))
  (:action putdown_vacuumcup_brighttable6
   :parameters ()
   :precondition (and (holding vacuumcup) (robotnear brighttable6))
   :effect (and (on vacuumcup brighttable6) (not (holding vacuumcup)) (increase (total-cost) 20)))
  (:action putdown_dessert_waterstation
   :parameters ()
   :precondition (and (holding dessert) (robotnear waterstation))
   :effect (and (on dessert waterstation) (not (holding dessert)) (increase (total-cost) 20)))
  (:action putdown_chips_table3
   :parameters ()
   :precondition (and (holding chips) (robotnear table3))
   :effect (and (on chips table3) (not (holding chips)) (increase (total-cost) 20)))
  (:action putdown_bottleddrink_table3
   :parameters ()
   :precondition (and (holding bottleddrink) (robotnear table3))
   :effect (and (on bottleddrink table3) (not (holding bottleddrink)) (increase (total-cost) 20)))
  (:action putdown_yogurt_bar
   :parameters ()
   :precondition (and (holding yogurt) (robotnear bar))
   :effect (and (on yogurt bar) (not (holding yogurt)) (increase (total-cost) 20)))
  (:action putdown_anything_anywhere
   :parameters ()
   :precondition (and )
   :effect (and (holding nothing) (not (holding admilk)) (not (holding bernachon)) (not (holding bottleddrink)) (not (holding chips)) (not (holding coffee)) (not (holding dessert)) (not (holding milk)) (not (holding milkdrink)) (not (holding nfcjuice)) (not (holding softdrink)) (not (holding springwater)) (not (holding vacuumcup)) (not (holding water)) (not (holding yogurt)) (increase (total-cost) 8)))
  (:action putdown_milkdrink_table1
   :parameters ()
   :precondition (and (holding milkdrink) (robotnear table1))
   :effect (and (on milkdrink table1) (not (holding milkdrink)) (increase (total-cost) 20)))
  (:action putdown_coffee_table1
   :parameters ()
   :precondition (and (holding coffee) (robotnear table1))
   :effect (and (on coffee table1) (not (holding coffee)) (increase (total-cost) 20)))
  (:action putdown_springwater_bar
   :parameters ()
   :precondition (and (holding springwater) (robotnear bar))
   :effect (and (on springwater bar) (not (holding springwater)) (increase (total-cost) 20)))
  (:action putdown_softdrink_table2
   :parameters ()
   :precondition (and (holding softdrink) (robotnear table2))
   :effect (and (on softdrink table2) (not (holding softdrink)) (increase (total-cost) 20)))
  (:action putdown_coffee_coffeestation
   :parameters ()
   :precondition (and (holding coffee) (robotnear coffeestation))
   :effect (and (on coffee coffeestation) (not (holding coffee)) (increase (total-cost) 20)))
  (:action putdown_water_brighttable6
   :parameters ()
   :precondition (and (holding water) (robotnear brighttable6))
   :effect (and (on water brighttable6) (not (holding water)) (increase (total-cost) 20)))
  (:action putdown_dessert_table1
   :parameters ()
   :precondition (and (holding dessert) (robotnear table1))
   :effect (and (on dessert table1) (not (holding dessert)) (increase (total-cost) 20)))
  (:action putdown_nfcjuice_brighttable6
   :parameters ()
   :precondition (and (holding nfcjuice) (robotnear brighttable6))
   :effect (and (on nfcjuice brighttable6) (not (holding nfcjuice)) (increase (total-cost) 20)))
  (:action putdown_admilk_table2
   :parameters ()
   :precondition (and (holding admilk) (robotnear table2))
   :effect (and (on admilk table2) (not (holding admilk)) (increase (total-cost) 20)))
  (:action putdown_vacuumcup_table2
   :parameters ()
   :precondition (and (holding vacuumcup) (robotnear table2))
   :effect (and (on vacuumcup table2) (not (holding vacuumcup)) (increase (total-cost) 20)))
  (:action putdown_softdrink_bar2
   :parameters ()
   :precondition (and (holding softdrink) (robotnear bar2))
   :effect (and (on softdrink bar2) (not (holding softdrink)) (increase (total-cost) 20)))
  (:action putdown_milkdrink_table3
   :parameters ()
   :precondition (and (holding milkdrink) (robotnear table3))
   :effect (and (on milkdrink table3) (not (holding milkdrink)) (increase (total-cost) 20)))
  (:action putdown_milk_bar
   :parameters ()
   :precondition (and (holding milk) (robotnear bar))
   :effect (and (on milk bar) (not (holding milk)) (increase (total-cost) 20)))
  (:action putdown_bernachon_bar
   :parameters ()
   :precondition (and (holding bernachon) (robotnear bar))
   :effect (and (on bernachon bar) (not (holding bernachon)) (increase (total-cost) 20)))
  (:action putdown_coffee_table3
   :parameters ()
   :precondition (and (holding coffee) (robotnear table3))
   :effect (and (on coffee table3) (not (holding coffee)) (increase (total-cost) 20)))
  (:action clean_table1
   :parameters ()
   :precondition (and (holding nothing))
   :effect (and (isclean table1) (increase (total-cost) 10)))
  (:action clean_floor
   :parameters ()
   :precondition (and (holding nothing))
   :effect (and (isclean floor) (increase (total-cost) 10)))
  (:action clean_chairs
   :parameters ()
   :precondition (and (holding nothing))
   :effect (and (isclean chairs) (increase (total-cost) 10)))
  (:action pickup_bernachon
   :parameters ()
   :precondition (and (holding nothing) (robotnear bernachon))
   :effect (and (holding bernachon) (not (exists_ bernachon)) (not (holding nothing)) (not (on bernachon bar)) (not (on bernachon bar2)) (not (on bernachon brighttable1)) (not (on bernachon brighttable2)) (not (on bernachon brighttable3)) (not (on bernachon brighttable4)) (not (on bernachon brighttable5)) (not (on bernachon brighttable6)) (not (on bernachon coffeestation)) (not (on bernachon coffeetable)) (not (on bernachon quiettable1)) (not (on bernachon quiettable2)) (not (on bernachon table1)) (not (on bernachon table2)) (not (on bernachon table3)) (not (on bernachon waterstation)) (not (on bernachon watertable)) (increase (total-cost) 2)))
  (:action pickup_admilk
   :parameters ()
   :precondition (and (holding nothing) (robotnear admilk))
   :effect (and (holding admilk) (not (exists_ admilk)) (not (holding nothing)) (not (on admilk bar)) (not (on admilk bar2)) (not (on admilk brighttable1)) (not (on admilk brighttable2)) (not (on admilk brighttable3)) (not (on admilk brighttable4)) (not (on admilk brighttable5)) (not (on admilk brighttable6)) (not (on admilk coffeestation)) (not (on admilk coffeetable)) (not (on admilk quiettable1)) (not (on admilk quiettable2)) (not (on admilk table1)) (not (on admilk table2)) (not (on admilk table3)) (not (on admilk waterstation)) (not (on admilk watertable)) (increase (total-cost) 2)))
  (:action pickup_chips
   :parameters ()
   :precondition (and (holding nothing) (robotnear chips))
   :effect (and (holding chips) (not (exists_ chips)) (not (holding nothing)) (not (on chips bar)) (not (on chips bar2)) (not (on chips brighttable1)) (not (on chips brighttable2)) (not (on chips brighttable3)) (not (on chips brighttable4)) (not (on chips brighttable5)) (not (on chips brighttable6)) (not (on chips coffeestation)) (not (on chips coffeetable)) (not (on chips quiettable1)) (not (on chips quiettable2)) (not (on chips table1)) (not (on chips table2)) (not (on chips table3)) (not (on chips waterstation)) (not (on chips watertable)) (increase (total-cost) 2)))
  (:action pickup_bottleddrink
   :parameters ()
   :precondition (and (holding nothing) (robotnear bottleddrink))
   :effect (and (holding bottleddrink) (not (exists_ bottleddrink)) (not (holding nothing)) (not (on bottleddrink bar)) (not (on bottleddrink bar2)) (not (on bottleddrink brighttable1)) (not (on bottleddrink brighttable2)) (not (on bottleddrink brighttable3)) (not (on bottleddrink brighttable4)) (not (on bottleddrink brighttable5)) (not (on bottleddrink brighttable6)) (not (on bottleddrink coffeestation)) (not (on bottleddrink coffeetable)) (not (on bottleddrink quiettable1)) (not (on bottleddrink quiettable2)) (not (on bottleddrink table1)) (not (on bottleddrink table2)) (not (on bottleddrink table3)) (not (on bottleddrink waterstation)) (not (on bottleddrink watertable)) (increase (total-cost) 2)))
  (:action pickup_yogurt
   :parameters ()
   :precondition (and (holding nothing) (robotnear yogurt))
   :effect (and (holding yogurt) (not (exists_ yogurt)) (not (holding nothing)) (not (on yogurt bar)) (not (on yogurt bar2)) (not (on yogurt brighttable1)) (not (on yogurt brighttable2)) (not (on yogurt brighttable3)) (not (on yogurt brighttable4)) (not (on yogurt brighttable5)) (not (on yogurt brighttable6)) (not (on yogurt coffeestation)) (not (on yogurt coffeetable)) (not (on yogurt quiettable1)) (not (on yogurt quiettable2)) (not (on yogurt table1)) (not (on yogurt table2)) (not (on yogurt table3)) (not (on yogurt waterstation)) (not (on yogurt watertable)) (increase (total-cost) 2)))
  (:action pickup_dessert
   :parameters ()
   :precondition (and (holding nothing) (robotnear dessert))
   :effect (and (holding dessert) (not (exists_ dessert)) (not (holding nothing)) (not (on dessert bar)) (not (on dessert bar2)) (not (on dessert brighttable1)) (not (on dessert brighttable2)) (not (on dessert brighttable3)) (not (on dessert brighttable4)) (not (on dessert brighttable5)) (not (on dessert brighttable6)) (not (on dessert coffeestation)) (not (on dessert coffeetable)) (not (on dessert quiettable1)) (not (on dessert quiettable2)) (not (on dessert table1)) (not (on dessert table2)) (not (on dessert table3)) (not (on dessert waterstation)) (not (on dessert watertable)) (increase (total-cost) 2)))
  (:action pickup_vacuumcup
   :parameters ()
   :precondition (and (holding nothing) (robotnear vacuumcup))
   :effect (and (holding vacuumcup) (not (exists_ vacuumcup)) (not (holding nothing)) (not (on vacuumcup bar)) (not (on vacuumcup bar2)) (not (on vacuumcup brighttable1)) (not (on vacuumcup brighttable2)) (not (on vacuumcup brighttable3)) (not (on vacuumcup brighttable4)) (not (on vacuumcup brighttable5)) (not (on vacuumcup brighttable6)) (not (on vacuumcup coffeestation)) (not (on vacuumcup coffeetable)) (not (on vacuumcup quiettable1)) (not (on vacuumcup quiettable2)) (not (on vacuumcup table1)) (not (on vacuumcup table2)) (not (on vacuumcup table3)) (not (on vacuumcup waterstation)) (not (on vacuumcup watertable)) (increase (total-cost) 2)))
  (:action pickup_nfcjuice
   :parameters ()
   :precondition (and (holding nothing) (robotnear nfcjuice))
   :effect (and (holding nfcjuice) (not (exists_ nfcjuice)) (not (holding nothing)) (not (on nfcjuice bar)) (not (on nfcjuice bar2)) (not (on nfcjuice brighttable1)) (not (on nfcjuice brighttable2)) (not (on nfcjuice brighttable3)) (not (on nfcjuice brighttable4)) (not (on nfcjuice brighttable5)) (not (on nfcjuice brighttable6)) (not (on nfcjuice coffeestation)) (not (on nfcjuice coffeetable)) (not (on nfcjuice quiettable1)) (not (on nfcjuice quiettable2)) (not (on nfcjuice table1)) (not (on nfcjuice table2)) (not (on nfcjuice table3)) (not (on nfcjuice waterstation)) (not (on nfcjuice watertable)) (increase (total-cost) 2)))
  (:action pickup_springwater
   :parameters ()
   :precondition (and (holding nothing) (robotnear springwater))
   :effect (and (holding springwater) (not (exists_ springwater)) (not (holding nothing)) (not (on springwater bar)) (not (on springwater bar2)) (not (on springwater brighttable1)) (not (on springwater brighttable2)) (not (on springwater brighttable3)) (not (on springwater brighttable4)) (not (on springwater brighttable5)) (not (on springwater brighttable6)) (not (on springwater coffeestation)) (not (on springwater coffeetable)) (not (on springwater quiettable1)) (not (on springwater quiettable2)) (not (on springwater table1)) (not (on springwater table2)) (not (on springwater table3)) (not (on springwater waterstation)) (not (on springwater watertable)) (increase (total-cost) 2)))
  (:action pickup_milk
   :parameters ()
   :precondition (and (holding nothing) (robotnear milk))
   :effect (and (holding milk) (not (exists_ milk)) (not (holding nothing)) (not (on milk bar)) (not (on milk bar2)) (not (on milk brighttable1)) (not (on milk brighttable2)) (not (on milk brighttable3)) (not (on milk brighttable4)) (not (on milk brighttable5)) (not (on milk brighttable6)) (not (on milk coffeestation)) (not (on milk coffeetable)) (not (on milk quiettable1)) (not (on milk quiettable2)) (not (on milk table1)) (not (on milk table2)) (not (on milk table3)) (not (on milk waterstation)) (not (on milk watertable)) (increase (total-cost) 2)))
  (:action pickup_milkdrink
   :parameters ()
   :precondition (and (holding nothing) (robotnear milkdrink))
   :effect (and (holding milkdrink) (not (exists_ milkdrink)) (not (holding nothing)) (not (on milkdrink bar)) (not (on milkdrink bar2)) (not (on milkdrink brighttable1)) (not (on milkdrink brighttable2)) (not (on milkdrink brighttable3)) (not (on milkdrink brighttable4)) (not (on milkdrink brighttable5)) (not (on milkdrink brighttable6)) (not (on milkdrink coffeestation)) (not (on milkdrink coffeetable)) (not (on milkdrink quiettable1)) (not (on milkdrink quiettable2)) (not (on milkdrink table1)) (not (on milkdrink table2)) (not (on milkdrink table3)) (not (on milkdrink waterstation)) (not (on milkdrink watertable)) (increase (total-cost) 2)))
  (:action pickup_softdrink
   :parameters ()
   :precondition (and (holding nothing) (robotnear softdrink))
   :effect (and (holding softdrink) (not (exists_ softdrink)) (not (holding nothing)) (not (on softdrink bar)) (not (on softdrink bar2)) (not (on softdrink brighttable1)) (not (on softdrink brighttable2)) (not (on softdrink brighttable3)) (not (on softdrink brighttable4)) (not (on softdrink brighttable5)) (not (on softdrink brighttable6)) (not (on softdrink coffeestation)) (not (on softdrink coffeetable)) (not (on softdrink quiettable1)) (not (on softdrink quiettable2)) (not (on softdrink table1)) (not (on softdrink table2)) (not (on softdrink table3)) (not (on softdrink waterstation)) (not (on softdrink watertable)) (increase (total-cost) 2)))
  (:action pickup_water
   :parameters ()
   :precondition (and (holding nothing) (robotnear water))
   :effect (and (holding water) (not (exists_ water)) (not (holding nothing)) (not (on water bar)) (not (on water bar2)) (not (on water brighttable1)) (not (on water brighttable2)) (not (on water brighttable3)) (not (on water brighttable4)) (not (on water brighttable5)) (not (on water brighttable6)) (not (on water coffeestation)) (not (on water coffeetable)) (not (on water quiettable1)) (not (on water quiettable2)) (not (on water table1)) (not (on water table2)) (not (on water table3)) (not (on water waterstation)) (not (on water watertable)) (increase (total-cost) 2)))
  (:action pickup_coffee
   :parameters ()
   :precondition (and (holding nothing) (robotnear coffee))
   :effect (and (holding coffee) (not (exists_ coffee)) (not (holding nothing)) (not (on coffee bar)) (not (on coffee bar2)) (not (on coffee brighttable1)) (not (on coffee brighttable2)) (not (on coffee brighttable3)) (not (on coffee brighttable4)) (not (on coffee brighttable5)) (not (on coffee brighttable6)) (not (on coffee coffeestation)) (not (on coffee coffeetable)) (not (on coffee quiettable1)) (not (on coffee quiettable2)) (not (on coffee table1)) (not (on coffee table2)) (not (on coffee table3)) (not (on coffee waterstation)) (not (on coffee watertable)) (increase (total-cost) 2)))
  (:action moveto_bernachon
   :parameters ()
   :precondition (and (exists_ bernachon))
   :effect (and (robotnear bernachon) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_coffeestation
   :parameters ()
   :precondition (and )
   :effect (and (robotnear coffeestation) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_watertable
   :parameters ()
   :precondition (and )
   :effect (and (robotnear watertable) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_yogurt
   :parameters ()
   :precondition (and (exists_ yogurt))
   :effect (and (robotnear yogurt) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (increase (total-cost) 15)))
  (:action moveto_bar2
   :parameters ()
   :precondition (and )
   :effect (and (robotnear bar2) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_bar
   :parameters ()
   :precondition (and )
   :effect (and (robotnear bar) (not (robotnear admilk)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_brighttable6
   :parameters ()
   :precondition (and )
   :effect (and (robotnear brighttable6) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_quiettable2
   :parameters ()
   :precondition (and )
   :effect (and (robotnear quiettable2) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_table3
   :parameters ()
   :precondition (and )
   :effect (and (robotnear table3) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_waterstation
   :parameters ()
   :precondition (and )
   :effect (and (robotnear waterstation) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_softdrink
   :parameters ()
   :precondition (and (exists_ softdrink))
   :effect (and (robotnear softdrink) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_table1
   :parameters ()
   :precondition (and )
   :effect (and (robotnear table1) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_brighttable4
   :parameters ()
   :precondition (and )
   :effect (and (robotnear brighttable4) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_water
   :parameters ()
   :precondition (and (exists_ water))
   :effect (and (robotnear water) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_milkdrink
   :parameters ()
   :precondition (and (exists_ milkdrink))
   :effect (and (robotnear milkdrink) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_brighttable1
   :parameters ()
   :precondition (and )
   :effect (and (robotnear brighttable1) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_admilk
   :parameters ()
   :precondition (and (exists_ admilk))
   :effect (and (robotnear admilk) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_chips
   :parameters ()
   :precondition (and (exists_ chips))
   :effect (and (robotnear chips) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_bottleddrink
   :parameters ()
   :precondition (and (exists_ bottleddrink))
   :effect (and (robotnear bottleddrink) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_table2
   :parameters ()
   :precondition (and )
   :effect (and (robotnear table2) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_dessert
   :parameters ()
   :precondition (and (exists_ dessert))
   :effect (and (robotnear dessert) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_vacuumcup
   :parameters ()
   :precondition (and (exists_ vacuumcup))
   :effect (and (robotnear vacuumcup) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_nfcjuice
   :parameters ()
   :precondition (and (exists_ nfcjuice))
   :effect (and (robotnear nfcjuice) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_springwater
   :parameters ()
   :precondition (and (exists_ springwater))
   :effect (and (robotnear springwater) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_milk
   :parameters ()
   :precondition (and (exists_ milk))
   :effect (and (robotnear milk) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_brighttable2
   :parameters ()
   :precondition (and )
   :effect (and (robotnear brighttable2) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_quiettable1
   :parameters ()
   :precondition (and )
   :effect (and (robotnear quiettable1) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_brighttable3
   :parameters ()
   :precondition (and )
   :effect (and (robotnear brighttable3) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_coffeetable
   :parameters ()
   :precondition (and )
   :effect (and (robotnear coffeetable) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_brighttable5
   :parameters ()
   :precondition (and )
   :effect (and (robotnear brighttable5) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffee)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action moveto_coffee
   :parameters ()
   :precondition (and (exists_ coffee))
   :effect (and (robotnear coffee) (not (robotnear admilk)) (not (robotnear bar)) (not (robotnear bar2)) (not (robotnear bernachon)) (not (robotnear bottleddrink)) (not (robotnear brighttable1)) (not (robotnear brighttable2)) (not (robotnear brighttable3)) (not (robotnear brighttable4)) (not (robotnear brighttable5)) (not (robotnear brighttable6)) (not (robotnear chips)) (not (robotnear coffeestation)) (not (robotnear coffeetable)) (not (robotnear dessert)) (not (robotnear milk)) (not (robotnear milkdrink)) (not (robotnear nfcjuice)) (not (robotnear quiettable1)) (not (robotnear quiettable2)) (not (robotnear softdrink)) (not (robotnear springwater)) (not (robotnear table1)) (not (robotnear table2)) (not (robotnear table3)) (not (robotnear vacuumcup)) (not (robotnear water)) (not (robotnear waterstation)) (not (robotnear watertable)) (not (robotnear yogurt)) (increase (total-cost) 15)))
  (:action make_coffee
   :parameters ()
   :precondition (and (holding nothing))
   :effect (and (exists_ coffee) (on coffee coffeestation) (increase (total-cost) 5)))
  (:action make_water
   :parameters ()
   :precondition (and (holding nothing))
   :effect (and (exists_ water) (on water waterstation) (increase (total-cost) 5)))
  (:action make_dessert
   :parameters ()
   :precondition (and (holding nothing))
   :effect (and (exists_ dessert) (on dessert bar) (increase (total-cost) 5)))
)
