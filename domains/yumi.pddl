; The paper's ABB Yumi scenario in PDDL: the twin of domains/yumi.bt (same domain but for
; the actions' durations, same default problem; the .bt file explains the model). Plan it with:
;   btplan plan domains/yumi.pddl
; A part must be held with its opening away from the gripper to be inserted; picking
; fixes the grasp (opening up -> away, down -> toward), and only a handover turns it.

(define (domain yumi)
  (:requirements :strips :typing :equality)
  (:types arm spot face grasp item - object part fixture - item)
  (:constants up down - face away toward - grasp)
  (:predicates
    (lies ?p - part ?s - spot ?f - face)
    (holds ?a - arm ?p - part ?g - grasp)
    (free ?a - arm)
    (mounted ?i - item)
    (reaches ?a - arm ?s - spot)
    (grasp_of ?f - face ?g - grasp)
    (turned ?g ?h - grasp)
    (needs ?p - part ?q ?r - item)
    (mounts ?a - arm))

  (:action Pick
    :parameters (?p - part ?a - arm ?s - spot ?f - face ?g - grasp)
    :precondition (and (reaches ?a ?s) (grasp_of ?f ?g) (lies ?p ?s ?f) (free ?a))
    :effect (and (holds ?a ?p ?g) (not (lies ?p ?s ?f)) (not (free ?a))))

  (:action Place
    :parameters (?p - part ?a - arm ?s - spot ?f - face ?g - grasp)
    :precondition (and (reaches ?a ?s) (grasp_of ?f ?g) (holds ?a ?p ?g))
    :effect (and (lies ?p ?s ?f) (free ?a) (not (holds ?a ?p ?g))))

  (:action Handover
    :parameters (?p - part ?giver ?taker - arm ?g ?h - grasp)
    :precondition (and (not (= ?giver ?taker)) (turned ?g ?h) (holds ?giver ?p ?g) (free ?taker))
    :effect (and (holds ?taker ?p ?h) (free ?giver) (not (holds ?giver ?p ?g)) (not (free ?taker))))

  (:action Insert
    :parameters (?p - part ?a - arm ?q ?r - item)
    :precondition (and (needs ?p ?q ?r) (mounts ?a) (mounted ?q) (mounted ?r) (holds ?a ?p away))
    :effect (and (mounted ?p) (free ?a) (not (holds ?a ?p away)))))

(define (problem phone)
  (:domain yumi)
  (:objects left right - arm left_side right_side middle floor - spot base - fixture chassis board battery camera cover screws - part)
  (:init
    (free left)
    (free right)
    (reaches left left_side)
    (reaches left middle)
    (reaches right right_side)
    (reaches right middle)
    (grasp_of up away)
    (grasp_of down toward)
    (turned away toward)
    (turned toward away)
    (mounted base)
    (mounts left)
    (mounts right)
    (needs chassis base base)
    (needs board chassis chassis)
    (needs battery board board)
    (needs camera board board)
    (needs cover battery camera)
    (needs screws cover cover)
    (lies chassis left_side down)
    (lies board right_side up)
    (lies battery left_side up)
    (lies camera right_side up)
    (lies cover left_side up)
    (lies screws right_side up)
  )
  (:goal (and (mounted chassis) (mounted board) (mounted battery) (mounted camera) (mounted cover) (mounted screws))))
