"""solve.py: options from settings, progress reports, gap arithmetic."""

from __future__ import annotations

import math

import pyomo.environ as pyo
import pytest

from layoutdsl.syntax.ast import Settings
from layoutdsl.model import build_model
from layoutdsl.solve import SolveOptions, _add_start, _translate, relative_gap, solve

from spec_cases import room, spec
from planted import planted


def test_flags_override_settings_and_unset_flags_keep_them():
    settings = Settings(time_limit=30, gap=0.05, seed=4, emphasis="feasibility", node_limit=100)
    options = SolveOptions.from_settings(settings, time_limit=5, seed=None, emphasis=None)
    assert (options.time_limit, options.gap, options.seed, options.emphasis, options.node_limit) == (
        5, 0.05, 4, "feasibility", 100)


def test_relative_gap_handles_signs_and_missing_bounds():
    assert relative_gap(10.0, 9.0) == pytest.approx(0.1)
    assert relative_gap(10.0, -5.0) == pytest.approx(1.5)  # SCIP's getGap says 1e20 here
    assert relative_gap(0.0, 0.0) == 0.0
    assert relative_gap(None, 1.0) is None
    assert relative_gap(3.0, -math.inf) == math.inf


def test_unknown_emphasis_is_refused():
    spec, _ = planted(2, 1)
    with pytest.raises(ValueError, match="emphasis"):
        solve(build_model(spec), SolveOptions(time_limit=1, emphasis="fast", quiet=True))


def test_long_solves_report_progress_about_every_second_and_a_half():
    spec, _ = planted(6, 3)  # 39 rooms: SCIP from scratch will not finish in 2.5 s
    calls = []
    outcome = solve(build_model(spec), SolveOptions(time_limit=2.5), progress=lambda *a: calls.append(a))
    assert outcome.seconds < 2.5 + 2.0
    assert len(calls) >= 1
    elapsed = [c[0] for c in calls]
    assert elapsed == sorted(elapsed) and all(0 < e < 6 for e in elapsed)
    for _, incumbent, gap in calls:
        assert (incumbent is None) == (gap is None)


def test_quiet_solves_report_nothing(capsys):
    spec, _ = planted(2, 1)
    solve(build_model(spec), SolveOptions(time_limit=1, quiet=True))
    assert capsys.readouterr().err == ""


def test_a_rejected_start_offered_to_one_scip_model_many_times_is_dropped_not_stored():
    # The neighbourhood search re-solves one SCIP model every round. Offering a start SCIP
    # rejects as a partial solution each round used to exhaust limits/maxorigsol (10) and
    # crash a 43-room compile; without the fallback such a start is simply not offered.
    two = spec("two", [room("A", (2, 3, 2.5), (2, 3, 2.5)), room("B", (2, 3, 2.5), (2, 3, 2.5))], 8, 8)
    model = build_model(two)
    for var in model.component_data_objects(ctype=pyo.Var):
        var.set_value(var.lb if var.lb is not None else 0, skip_validation=True)
    for r in ("A", "B"):  # both rooms on the same spot: the start violates non-overlap
        model.x[r].set_value(0)
        model.y[r].set_value(0)
        model.w[r].set_value(2.5)
        model.h[r].set_value(2.5)
    interface, scip_model, _loader = _translate(model)
    for _ in range(15):
        scip_model.freeTransform()
        assert _add_start(interface, scip_model, model, False, partial_fallback=False) is False
    scip_model.freeProb()


def test_a_neighbourhood_takes_the_rooms_across_a_rooms_walls_before_nearer_centres():
    from layoutdsl.solve import _nearest_rooms

    # K a 20 m corridor; A touches its left end from above, B's centre is nearer K's centre
    # but 3.5 m clear of it
    corridor = spec("corridor", [room("K", (10, 20, 20), (2, 3, 2), rtype="C"), room("A", (3, 4, 3), (3, 4, 3)),
                                 room("B", (3, 4, 3), (3, 4, 3))], 22, 10)
    model = build_model(corridor)
    for r, (x, y, w, h) in {"K": (0, 0, 20, 2), "A": (0, 2.2, 3, 3), "B": (8.5, 5.5, 3, 3)}.items():
        model.x[r].set_value(x)
        model.y[r].set_value(y)
        model.w[r].set_value(w)
        model.h[r].set_value(h)
    assert _nearest_rooms(model, "K", 2) == {"K", "A"}
    assert _nearest_rooms(model, "K", 3) == {"K", "A", "B"}


def _values(model):
    return [v.value for v in model.component_data_objects(pyo.Var, active=True)]


def test_work_limits_stop_a_solve_at_the_same_point_whatever_the_time_limit():
    # the wall clock is only the outer cap: two generous caps give the same layout, bit for bit
    # caps far above the work (a few seconds idle): a loaded test machine must not reach them
    spec, _ = planted(2, 1)
    results = []
    for cap in (300.0, 900.0):
        model = build_model(spec)
        outcome = solve(model, SolveOptions(time_limit=cap, quiet=True, node_limit=40, seed=3))
        assert outcome.status in ("node_limit", "optimal", "gap_limit") and not outcome.wall_clock_limited
        results.append((outcome.status, outcome.nodes, outcome.lp_iterations, _values(model)))
    assert results[0] == results[1]


def test_an_iteration_budget_stops_a_solve_deterministically():
    spec, _ = planted(3, 2)
    runs = []
    for _ in range(2):
        model = build_model(spec)
        outcome = solve(model, SolveOptions(time_limit=600, quiet=True, lp_iteration_limit=300, seed=1))
        assert outcome.status == "iteration_limit" and not outcome.wall_clock_limited
        assert outcome.lp_iterations >= 300
        runs.append((outcome.nodes, outcome.lp_iterations, outcome.has_solution))
    assert runs[0] == runs[1]


def test_a_solve_stopped_by_the_wall_clock_says_so():
    spec, _ = planted(6, 3)  # 39 rooms from scratch: no deterministic limit comes first in 1 s
    outcome = solve(build_model(spec), SolveOptions(time_limit=1.0, quiet=True, node_limit=10**9,
                                                    lp_iteration_limit=10**12))
    assert outcome.status == "time_limit" and outcome.wall_clock_limited
