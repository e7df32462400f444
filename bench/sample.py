"""How close are sampled room graphs to real plans, how new are they, and do they compile?

    python bench/sample.py                      # realism + novelty, 1,000 samples (about a minute)
    python bench/sample.py -n 200 --seed 3      # smaller, another seed
    python bench/sample.py --compile 50         # also compile 50 specs of the shipped model
    python bench/sample.py --compile 200 --first-layout --skip-realism   # only success and time to a layout

Realism (issue 41): the 24 real plans sorted by file name are split alternately, plans 1, 3,
5, ... to train (the grammar and the size model are fitted on them alone) and plans 2, 4, 6,
... to test; both halves mix schools and offices. N samples are drawn `--like any` (each from
a training plan of either kind as template). For each statistic of layoutdsl.sample.stats the
table gives GraphRNN's MMD² (Gaussian kernel on the total-variation distance between
histograms) between the training half and the test half (the baseline: how far two sets of
real plans are from each other) and between the samples and the test half; the acceptance
is MMD²(samples, test) <= 2 x MMD²(train, test) for every statistic.

Novelty: how many samples are isomorphic (bare topology) to a training graph, checked here
with networkx's VF2 on every same-size pair, independently of the sampler's own check; and
each sample's nearest-neighbour similarity to the training graphs under the normalized
Weisfeiler-Lehman subtree kernel (node types as labels, 3 rounds), beside the same figure
for the real test plans (how similar a real plan is to the nearest other real plan).

Compile (`--compile K`): the first K specs of `layoutdsl sample --like any` from the
shipped model, each through `layoutdsl compile --time-limit 60` in turn; how many give a
verified layout, and the first-layout times read from the layout JSON. With `--first-layout`
each compile (in a process of its own) stops at its first verified layout, as a dataset's
buildings do, instead of searching on for the rest of the minute. Timings depend on the
machine's load.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import networkx as nx

from layoutdsl.sample import SpecSampler, fit_grammar, load_grammar
from layoutdsl.sample import stats
from layoutdsl.sample.corpus import read_corpus
from layoutdsl.sample.novelty import wl_features, wl_similarity
from layoutdsl.sizes.fit import fit_model

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_FOLDER = ROOT.parent / "shared" / "floorplans"
ACCEPT_RATIO = 2.0


def split(files: list[Path]) -> tuple[list[Path], list[Path]]:
    """Alternate by sorted name: 1st, 3rd, ... to train; 2nd, 4th, ... to test."""
    files = sorted(files)
    return files[0::2], files[1::2]


def sampled_graphs(grammar, sizes, count: int, seed: int, like: str = "any", drawn: bool = True) -> list[nx.Graph]:
    """N sampled graphs with each room's area (m²) from its spec's target sides."""
    sampler = SpecSampler(grammar, like, sizes, seed=seed, drawn_sizes=drawn)
    graphs = []
    for index in range(1, count + 1):
        sample = sampler.sample(index)
        graph = sample.graph.copy()
        for node, room in zip(graph.nodes, sample.spec.rooms):  # spec_from_graph keeps node order
            area = room.target_w * room.target_h
            arm = sample.spec.arm(room.id)
            graph.nodes[node]["area"] = area + (arm.target_w * arm.target_h if arm else 0.0)
        graphs.append(graph)
    return graphs


def realism_table(train: list[nx.Graph], test: list[nx.Graph], samples: list[nx.Graph]) -> tuple[list[str], bool]:
    lines = [
        f"{'statistic':16s} {'MMD2(train,test)':>17s} {'MMD2(samples,test)':>19s} {'ratio':>6s}  <= {ACCEPT_RATIO:g}x",
    ]
    passed = True
    for statistic in stats.STATISTICS:
        baseline = stats.statistic_mmd2(statistic, train, test)
        value = stats.statistic_mmd2(statistic, samples, test)
        ratio = value / baseline if baseline > 0 else float("inf")
        ok = value <= ACCEPT_RATIO * baseline
        passed &= ok
        lines.append(f"{statistic.name:16s} {baseline:17.4f} {value:19.4f} {ratio:6.2f}  {'yes' if ok else 'NO'}")
    return lines, passed


def means_table(sets: dict[str, list[nx.Graph]]) -> list[str]:
    lines = [f"{'set':10s} {'graphs':>6s} {'rooms':>12s} {'corridor %':>10s} {'entrances':>9s} "
             f"{'cycle rank':>10s} {'mean degree':>11s} {'clustering':>10s}"]
    for name, graphs in sets.items():
        rooms = [g.number_of_nodes() for g in graphs]
        share = [100 * sum(1 for n in g if g.nodes[n]["rtype"] == "C") / g.number_of_nodes() for g in graphs]
        entrances = [sum(1 for n in g if g.nodes[n]["rtype"] == "E") for g in graphs]
        cycles = [stats.cycle_rank(g) for g in graphs]
        degree = [2 * g.number_of_edges() / g.number_of_nodes() for g in graphs]
        clustering = [nx.average_clustering(g) for g in graphs]
        lines.append(
            f"{name:10s} {len(graphs):6d} {statistics.mean(rooms):5.1f} ({min(rooms)}-{max(rooms)}) "
            f"{statistics.mean(share):10.1f} {statistics.mean(entrances):9.2f} {statistics.mean(cycles):10.2f} "
            f"{statistics.mean(degree):11.2f} {statistics.mean(clustering):10.3f}"
        )
    return lines


def isomorphic_count(samples: list[nx.Graph], known: list[nx.Graph]) -> int:
    copies = 0
    for graph in samples:
        for other in known:
            if (other.number_of_nodes(), other.number_of_edges()) == (graph.number_of_nodes(), graph.number_of_edges()) \
                    and nx.is_isomorphic(other, graph):
                copies += 1
                break
    return copies


def distinct_count(graphs: list[nx.Graph]) -> int:
    """Samples up to isomorphism (WL hash buckets, then VF2 within a bucket)."""
    import warnings

    buckets: dict[str, list[nx.Graph]] = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        for graph in graphs:
            bucket = buckets.setdefault(nx.weisfeiler_lehman_graph_hash(graph, iterations=3), [])
            if not any(nx.is_isomorphic(graph, other) for other in bucket):
                bucket.append(graph)
    return sum(len(b) for b in buckets.values())


def nearest_similarity(graphs: list[nx.Graph], known: list[nx.Graph]) -> list[float]:
    known_features = [wl_features(g) for g in known]
    return [max(wl_similarity(wl_features(g), other) for other in known_features) for g in graphs]


def describe(values: list[float]) -> str:
    ordered = sorted(values)
    return (f"min {ordered[0]:.3f}, median {statistics.median(ordered):.3f}, mean {statistics.mean(ordered):.3f}, "
            f"max {ordered[-1]:.3f}")


def novelty_lines(samples: list[nx.Graph], train: list[nx.Graph], test: list[nx.Graph]) -> list[str]:
    copies = isomorphic_count(samples, train)
    similarity = nearest_similarity(samples, train)
    real = nearest_similarity(test, train)
    above = sum(1 for s in similarity if s > max(real))
    return [
        f"isomorphic to a training graph (VF2, bare topology): {copies} of {len(samples)}",
        f"isomorphic to a test graph:                          {isomorphic_count(samples, test)} of {len(samples)}",
        f"distinct samples (up to isomorphism):                {distinct_count(samples)} of {len(samples)}",
        f"nearest-neighbour WL similarity to the training graphs (1 = WL cannot tell them apart):",
        f"  samples     {describe(similarity)}",
        f"  test plans  {describe(real)}  (real plans, for scale)",
        f"  samples more similar to a training graph than any test plan is: {above} of {len(samples)}",
    ]


def _first_layout(text: str, name: str, time_limit: float) -> dict:
    """Lint a sampled spec's text and compile it as `layoutdsl compile` does, stopping at
    its first verified layout (the generator's, polished; no whole-model search after)."""
    from layoutdsl.api import lint_source
    from layoutdsl.compile import compile_spec
    from layoutdsl.diagnostics import has_errors
    from layoutdsl.diagnostics.source import Source
    from layoutdsl.solve import SolveOptions

    spec, diagnostics = lint_source(Source(f"{name}.lay", text))
    if spec is None or has_errors(diagnostics):
        return {"ok": False, "why": "lint"}
    result = compile_spec(spec, SolveOptions(time_limit=time_limit, seed=0, quiet=True, search=False))
    if result.layout is None:
        return {"ok": False, "why": " ".join(d.code for d in result.diagnostics)}
    return {"ok": True, "first": result.layout.solve.first_feasible_seconds}


def compile_snapshot(count: int, seed: int, time_limit: float, drawn: bool = True,
                     first_layout: bool = False) -> list[str]:
    """Compile the first `count` samples of the shipped model, one after the other
    (`first_layout`: each stops at its first verified layout, in a process of its own)."""
    from layoutdsl.devtools.isolation import run_isolated

    layoutdsl = Path(sys.executable).parent / "layoutdsl"
    sampler = SpecSampler(load_grammar(), "any", seed=seed, drawn_sizes=drawn)
    rows, firsts, ok = [], [], 0
    with tempfile.TemporaryDirectory(prefix="bench-sample-") as folder:
        for index in range(1, count + 1):
            sample = sampler.sample(index)
            spec = Path(folder) / f"{sample.name}.lay"
            spec.write_text(sample.text)
            began = time.monotonic()
            first = None
            if first_layout:
                outcome = run_isolated(_first_layout, sample.text, sample.name, time_limit, limit=time_limit + 60)
                compiled = bool(outcome.get("ok"))
                verdict = "yes" if compiled else f"no ({outcome.get('why') or outcome.get('status')})"
                first = outcome.get("first")
            else:
                process = subprocess.run(
                    [str(layoutdsl), "compile", str(spec), "-o", folder, "--time-limit", f"{time_limit:g}",
                     "--emit", "xml", "-q"], capture_output=True, text=True, timeout=3 * time_limit + 120)
                layout_file = Path(folder) / f"{sample.name}.layout.json"
                compiled = process.returncode == 0 and layout_file.exists()
                verdict = "yes" if compiled else f"no (exit {process.returncode})"
                if compiled:
                    first = json.loads(layout_file.read_text())["solve"].get("first_feasible_seconds")
            seconds = time.monotonic() - began
            if compiled:
                ok += 1
                if first is not None:
                    firsts.append(first)
            row = (f"{sample.name:9s} {sample.graph.graph['template'][:34]:34s} {sample.graph.number_of_nodes():5d} "
                   f"{verdict[:24]:>24s} {'-' if first is None else f'{first:.2f}':>9s} {seconds:8.1f}")
            rows.append(row)
            print(row, file=sys.stderr, flush=True)
    lines = [f"{'sample':9s} {'template':34s} {'rooms':>5s} {'compiles':>24s} {'first (s)':>9s} {'wall (s)':>8s}", *rows]
    lines.append(f"verified layouts: {ok} of {count} ({100 * ok / count:.0f} %) within --time-limit {time_limit:g}")
    if firsts:
        lines.append(f"first layout: median {statistics.median(firsts):.2f} s, "
                     f"max {max(firsts):.2f} s over the {len(firsts)} that compiled")
    return lines


def git_commit() -> str:
    try:
        return subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--plans", default=str(DEFAULT_FOLDER), help="folder of real plans (default ../shared/floorplans)")
    parser.add_argument("-n", "--samples", type=int, default=1000, help="samples to compare (default 1000)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--compile", type=int, default=0, metavar="K", help="also compile K specs of the shipped model")
    parser.add_argument("--time-limit", type=float, default=60.0, help="per compile (default 60)")
    parser.add_argument("--first-layout", action="store_true",
                        help="--compile: each compile stops at its first verified layout (no whole-model search)")
    parser.add_argument("--typical-sizes", action="store_true",
                        help="give sampled rooms each label's typical sizes instead of drawn ones")
    parser.add_argument("--skip-realism", action="store_true", help="only the compile snapshot")
    parser.add_argument("--out", help="also write the report to this file")
    args = parser.parse_args(argv)

    sizing = "typical sizes" if args.typical_sizes else "drawn sizes"
    lines: list[str] = []
    passed = True
    if not args.skip_realism:
        files = sorted(Path(args.plans).glob("*.xml"))
        if len(files) < 4:
            parser.error(f"{args.plans} holds {len(files)} plans; the split needs at least 4")
        train_files, test_files = split(files)
        began = time.monotonic()
        train_plans, test_plans = read_corpus(train_files), read_corpus(test_files)
        grammar = fit_grammar(train_plans, source="bench/sample.py training half")
        sizes = fit_model(train_files, corpus="bench/sample.py training half")
        samples = sampled_graphs(grammar, sizes, args.samples, args.seed, drawn=not args.typical_sizes)
        sampled_seconds = time.monotonic() - began
        train = [p.graph for p in train_plans]
        test = [p.graph for p in test_plans]
        lines += [
            f"bench/sample.py at commit {git_commit()}: {args.samples} samples, seed {args.seed}, like any, {sizing}",
            f"train ({len(train_files)}): {', '.join(p.stem for p in train_files)}",
            f"test  ({len(test_files)}): {', '.join(p.stem for p in test_files)}",
            f"grammar and size model fitted on the training half only; fit + {args.samples} samples "
            f"in {sampled_seconds:.1f} s (shared 2-core machine, under load)",
            "",
            "MMD² as GraphRNN (Gaussian kernel on total variation; σ = 1, clustering σ = 0.1):",
        ]
        table, passed = realism_table(train, test, samples)
        lines += table
        lines.append(f"acceptance (every statistic <= {ACCEPT_RATIO:g} x baseline): {'met' if passed else 'NOT met'}")
        lines += ["", "means:"] + means_table({"train": train, "test": test, "samples": samples})
        lines += ["", "novelty:"] + novelty_lines(samples, train, test)
    if args.compile:
        lines += ["", f"compile snapshot at commit {git_commit()}: the first {args.compile} specs of "
                  f"`layoutdsl sample --like any --seed {args.seed}{' --typical-sizes' if args.typical_sizes else ''}` "
                  f"(shipped model, {sizing}), each `layoutdsl compile --time-limit {args.time_limit:g}`"
                  f"{' stopped at its first verified layout' if args.first_layout else ''}, one at a time:"]
        lines += compile_snapshot(args.compile, args.seed, args.time_limit, drawn=not args.typical_sizes,
                                  first_layout=args.first_layout)
    report = "\n".join(lines) + "\n"
    print(report, end="")
    if args.out:
        Path(args.out).write_text(report)
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
