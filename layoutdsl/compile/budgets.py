"""Every limit a compile runs under, in one place.

WORK holds the work limits that decide results (moves, rounds, nodes): the same spec and
seed give the same layout on an idle machine and a loaded one. TIME holds the shares of the
wall-clock time limit: they only ever cut a stage off (the compile then says so), never
change what a stage that finishes returns.
"""

from __future__ import annotations

WORK = {
    # the schedule (schedule.py)
    "moves_per_room": 1500,      # moves per room in a chain of the first round
    "round_growth": 2.0,         # each round's chains make this many times the moves of the last
    "max_moves": 3_000_000,      # at most this many moves a chain
    "max_rounds": 8,             # rounds before the generator gives up (the last after a turn)
    "chains": 2,                 # chains side by side in a round (one per core measured on)
    "start_temperature": 0.02,   # x (outline width + height): metres of cost at the first move
    "end_temperature": 0.0001,   # ... at the last move
    "zero_stop": 0.3,            # a chain at violation 0 stops after this share of its moves
    "give_up_at": 0.6,           # a chain still more than give_up_m from a layout at this
    "give_up_m": 5.0,            #   share of its moves stops there
    "turn_after_rounds": (1,),   # after these rounds (0-based) a corridor of each unmet corridor-corridor
                                 #   door turns a corner (shapes.with_turns)
    # the sizing stage (layoutdsl.solve.relations): a round's MIP stops after this many nodes
    "repair_round_nodes": 200,
    "hint_round_nodes": 5000,    # ... a round's MIP on the original plan's boxes (worth a long repair)
    "repair_max_violation_m": 2.0,  # a round's best state is sized when at most this far from a layout
                                    #   (6.0 before an L's arm turned with its box: the repair of a
                                    #   state 3-5 m away then failed after 6-9 s on the slow plans,
                                    #   and the next round reached 0 and sized in 0.2 s). 1.0 was
                                    #   tried: on the 24 plans (seeds 0-1) and the 10 slowest graphs
                                    #   every sizing from 1.36-1.82 m had failed, after 1.5-27.8 s, but
                                    #   over all 80 graphs it cost more than it saved: 5 graphs sized
                                    #   early from 1-2 m now took more rounds (cml_new_17 1.7 -> 8.5 s,
                                    #   cml_new_220 1.3 -> 9.7 s), cml_new_270 alone gained (39 -> 33 s)
    # a derived arrangement (generator.derive): a found layout's state kicked by trades, one
    # chain, sized like a round's best. Measured from seed 0's state, seconds per layout
    # 0.3 or more from its origin (kicks tried): office_floorplanMAIN 3 trades and 3000 moves
    # a room 5.1 s (56), 4 and 6000 10.8 s (24), 4 and 12000 8.5 s (24), 2 and 6000 15.8 s
    # (24), half this temperature 6.3 s (32); school_wilbraham 3 / 3000 3.6 s, 4 / 6000 4.2 s
    # (24 each); office_floorplanLOWER none (its kicks that find a layout again lie 0.22-0.26
    # from it; 5 trades find none). A chain at the rounds' own start temperature (20x) lost
    # the layout and found none.
    # A walk of chains, each kicked from the last one that met every door, kept office_floorplanMAIN
    # going once its seed-0 layout came from a pulled start (kicks of it met again within 0.18-0.29
    # of it or not at all): derived layouts kept 0.3 or more from every earlier one, from 30-40
    # kicks, one core: 1 chain 0, 4 chains 5 (12.3 s each), 6 chains of 2 trades 9 (12.3 s),
    # 4 chains at 3x this temperature 5 (13.5 s); school_wilbraham 1 chain 0, 4 chains 2;
    # office_floorplanLOWER 1 chain 1, 4 chains 2.
    "derive_trades": 3,
    "derive_steps": 4,
    "derive_walk_m": 0.05,         # a chain that ends this near a layout is the next one's start
    "derive_moves_per_room": 3000,
    "derive_temperature": 0.001,
    "derive_min_difference": 0.3,  # a derived state nearer its origin is not sized (variants' MIN_PAIRWISE)
    "derive_repair_rounds": 2,     # fewer than a round's: one sizing failed after 43 s with 4, 1.8 s with 2
    # growing a found state towards its rooms' targets (schedule.grown) before it is sized:
    # the rounds draw rooms smaller than their targets (initial.PACKING_DENSITY), and with
    # the relations of so small a packing fixed the sizing LP could not grow them back (room
    # area 0.79-0.88 of the original on four plans). Each step draws the rooms a fifth
    # nearer their targets, at least grow_floor of that size, and one chain mends the doors
    # that moved; the last step that ends within grow_tolerance_m of a layout is sized.
    # Measured (compile, seed 0, room area / the original's): school_UMTDSchoolFloorplan
    # 0.820 -> 0.888, school_Lamuniere1 0.845 -> 0.925, school_Ursy1 0.921 -> 1.003; over the
    # 24 plans area within 10 % 11 -> 14 of 23 (bench/results/generation-plans.txt). Two
    # steps at 1500 moves a room and 0.001 (derive's temperature) mostly failed at the first;
    # 1500 moves at five steps lost UMTD's gain; two chains a step (the first that succeeds)
    # changed areas both ways and cost 0.1-0.5 s more.
    "grow_steps": 5,
    "grow_moves_per_room": 3000,
    "grow_temperature": 0.003,
    "grow_floor": 0.97,
    "grow_tolerance_m": 0.01,
    "repair_rounds": 4,          # repair rounds of an annealed state before the next round anneals
    "repair_stalls": 1,          # ... or stalled rounds
    "final_nodes": 2000,         # the final sizing LP/MIP with every relation fixed
}

TIME = {
    "generate": 0.8,   # share of the time limit the generator may use before it is cut off
    "probe": 0.05,     # SCIP's presolve-only infeasibility probe (at most 5 s)
    "polish": 0.1,     # polishing the generated layout with its relations fixed (solve.polish)
    "compact": 0.1,    # at least, the best layout's enclosed voids closed (solve.relations.compacted),
    "slivers": 0.1,    # and its slivers shut or opened (without_slivers): both may run to the deadline
    "lns": {True: 0.7, False: 0.9},  # share of what is left for neighbourhood search, for
                                     # specs of at most / more than LNS_SMALL rooms
}

LNS_SMALL = 20
"""Rooms up to which branch-and-bound over the whole model still closes the gap after the
neighbourhood search (school_fig42, 17 rooms: 1.6 % in 12 s; 76-105 rooms: nothing)."""

LNS_SIZE = 4
"""Rooms freed per neighbourhood (school_fig42, 10 s: 4 rooms reached 29.1, 6 rooms 29.5,
8 rooms 32.0 from a polished start of 35.7)."""
