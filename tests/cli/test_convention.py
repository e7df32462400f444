"""One CLI convention across all subcommands (issue 42), one test per inconsistency it listed.

Most tests call `layoutdsl.cli.main` in-process (fast); colour needs a real terminal, so
those tests run the command on a pseudo-terminal.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from layoutdsl.cli import COMMANDS, build_parser, main
from layoutdsl.diagnostics import exitcodes

ROOT = Path(__file__).resolve().parents[2]
DIAGNOSTICS = ROOT / "tests" / "diagnostics"
PLAN = ROOT / "examples" / "floorplans" / "school_Lamuniere1.xml"
TINY = ROOT / "tests" / "batch" / "fixtures" / "tiny.lay"
GOOD = "rooms\nR0 4 6 5 3 5 4 1 2 R OFFICE\nR1 4 6 5 3 5 4 1 2 R OFFICE\n\nboundary\n12 14\n\nadjacencies\nR0 R1 0.9 e\n"
ANSI = re.compile(r"\x1b\[[0-9;]*m")


def subparser(name: str):
    parser = build_parser(name)
    action = next(a for a in parser._actions if a.dest == "command")
    return action.choices[name]


def options(name: str) -> dict[str, object]:
    return {flag: action for action in subparser(name)._actions for flag in action.option_strings}


def run_main(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


# ----------------------------------------------------------------- -q / -v / --format


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_every_command_takes_quiet_verbose_and_format_text_or_json(name):
    flags = options(name)
    assert {"-q", "--quiet", "-v", "--verbose", "--format"} <= set(flags), name
    assert {"text", "json"} <= set(flags["--format"].choices), name
    assert flags["--format"].default == "text"


def test_quiet_means_no_progress_and_no_summary_but_diagnostics(capsys):
    code, out, err = run_main(capsys, "lint", "-q", str(DIAGNOSTICS / "E102_unknown_adjacent_room.lay"))
    assert code == 1 and "error[E102]" in out and "found 2 errors" not in out and err == ""
    code, out, err = run_main(capsys, "lint", str(DIAGNOSTICS / "E102_unknown_adjacent_room.lay"))
    assert out.rstrip().endswith("found 2 errors")


def test_quiet_import_prints_no_summary_and_verbose_prints_the_steps(tmp_path, capsys):
    target = tmp_path / "plan.lay"
    code, out, err = run_main(capsys, "import", str(PLAN), "-o", str(target), "-q")
    assert code == 0 and out == "" and err == ""
    code, out, err = run_main(capsys, "import", str(PLAN), "-o", str(target))
    assert code == 0 and err.startswith("imported ")
    code, out, err = run_main(capsys, "import", str(PLAN), "-o", str(target), "-v")
    assert f"reading {PLAN}" in err and f"wrote {target}" in err and "done in" in err


def test_quiet_and_verbose_exclude_each_other(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["lint", "-q", "-v", "x.lay"])
    assert stop.value.code == exitcodes.USAGE


# ----------------------------------------------------------------- JSON results


def json_result(capsys, *argv: str) -> tuple[int, dict]:
    code, out, _ = run_main(capsys, *argv, "--format", "json")
    result = json.loads(out)  # stdout is exactly one JSON object
    assert result["exit_code"] == code and result["status"] == exitcodes.STATUS[code]
    assert {"command", "read", "written", "diagnostics", "errors", "timings"} <= set(result)
    assert result["timings"]["total_s"] >= 0
    return code, result


def test_json_result_of_lint_and_fmt(tmp_path, capsys):
    spec = tmp_path / "a.lay"
    spec.write_text(GOOD)
    code, result = json_result(capsys, "lint", str(spec))
    assert (code, result["command"], result["files"]) == (0, "lint", [str(spec)])
    code, result = json_result(capsys, "fmt", str(spec))
    assert code == 0 and result["formatted"][str(spec)].startswith("rooms\n")
    messy = tmp_path / "b.lay"
    messy.write_text(GOOD.replace("R0 R1 0.9", "R0   R1 .9"))
    code, result = json_result(capsys, "fmt", "--write", str(messy))
    assert code == 0 and result["written"] == [str(messy)] and result["changed"] == [str(messy)]


def test_json_result_of_compile_says_what_was_written(tmp_path, capsys):
    outdir = tmp_path / "new" / "folder"  # created (issue 42: output folders created)
    code, result = json_result(capsys, "compile", str(TINY), "-o", str(outdir), "--emit", "xml",
                               "--node-limit", "5", "-q")
    assert code == 0
    assert sorted(Path(p).name for p in result["written"]) == ["tiny.layout.json", "tiny.xml"]
    assert all(Path(p).is_file() for p in result["written"])
    assert result["layout"]["rooms"] == 3 and result["layout"]["solve_status"]
    assert {"lint_s", "solve_s", "write_s"} <= set(result["timings"])


def test_json_result_of_compile_on_spec_errors(tmp_path, capsys):
    bad = tmp_path / "bad.lay"
    bad.write_text(GOOD.replace("R0 R1", "R0 R9"))
    code, result = json_result(capsys, "compile", str(bad), "-o", str(tmp_path / "out"))
    assert code == 1 and [d["code"] for d in result["diagnostics"]] == ["E102"]
    assert result["diagnostics"][0]["help"] == "did you mean `R1`?"
    assert not (tmp_path / "out").exists()


def test_json_result_of_import_and_evaluate(tmp_path, capsys):
    spec = tmp_path / "deep" / "plan.lay"  # `import -o out/x.lay` creates out/
    code, result = json_result(capsys, "import", str(PLAN), "-o", str(spec))
    assert code == 0 and result["written"] == [str(spec)] and spec.is_file()
    assert result["rooms"] == 8
    code, result = json_result(capsys, "evaluate", str(PLAN), str(PLAN), "-o", str(tmp_path / "report"),
                               "--resolution", "0.2", "--explore-resolution", "0.4", "-q")
    assert code == 0 and Path(result["report"]).is_file()
    assert str(tmp_path / "report" / "report.json") in result["written"]


def test_json_result_of_explain(capsys):
    code, out, _ = run_main(capsys, "explain", "E102", "--format", "json")
    assert code == 0 and json.loads(out)


# ----------------------------------------------------------------- one I/O error style


@pytest.mark.parametrize("argv", [
    ["lint", "{missing}"],
    ["fmt", "{missing}"],
    ["compile", "{missing}", "-o", "{tmp}/out"],
    ["import", "{missing}", "-o", "{tmp}/x.lay"],
    ["evaluate", "{missing}", "{missing}", "-o", "{tmp}/report"],
    ["batch", "{missing}", "-o", "{tmp}/data"],
])
def test_a_missing_file_is_one_style_and_exit_2(argv, tmp_path, capsys):
    missing = tmp_path / "missing.lay"
    argv = [word.format(missing=missing, tmp=tmp_path) for word in argv]
    code, out, err = run_main(capsys, *argv)
    assert code == exitcodes.USAGE
    assert err == f"layoutdsl {argv[0]}: error: cannot read `{missing}`: no such file or directory\n"
    assert "no problems found" not in out  # lint used to say so after failing to read a file
    assert not (tmp_path / "out").exists() and not (tmp_path / "data").exists()


def test_a_directory_and_a_binary_file_are_the_same_style(tmp_path, capsys):
    binary = tmp_path / "bin.lay"
    binary.write_bytes(b"rooms\n\xff\xfe")
    code, _, err = run_main(capsys, "compile", str(binary), "-o", str(tmp_path / "o"))
    assert (code, err) == (2, f"layoutdsl compile: error: cannot read `{binary}`: not UTF-8 text (byte 6)\n")
    code, _, err = run_main(capsys, "import", str(tmp_path), "-o", str(tmp_path / "x.lay"))
    assert (code, err) == (2, f"layoutdsl import: error: cannot read `{tmp_path}`: is a directory\n")


def test_lint_counts_what_it_read_and_what_it_could_not(tmp_path, capsys):
    good = tmp_path / "good.lay"
    good.write_text(GOOD)
    code, out, err = run_main(capsys, "lint", str(good), str(tmp_path / "gone.lay"))
    assert code == 2 and "cannot read" in err
    assert out == "checked 1 file; 1 could not be read\n"


# ----------------------------------------------------------------- folders


def test_lint_and_fmt_take_folders_recursively(tmp_path, capsys):
    (tmp_path / "a" / "b").mkdir(parents=True)
    (tmp_path / "a" / "one.lay").write_text(GOOD)
    (tmp_path / "a" / "b" / "two.lay").write_text(GOOD.replace("R0 R1", "R0 R9"))
    (tmp_path / "a" / "b" / "notes.txt").write_text("not a spec")
    (tmp_path / "a" / ".hidden").mkdir()
    (tmp_path / "a" / ".hidden" / "skip.lay").write_text("garbage")
    code, out, _ = run_main(capsys, "lint", "--format", "concise", str(tmp_path / "a"))
    assert code == 1
    assert out == f"{tmp_path / 'a' / 'b' / 'two.lay'}:9:4: E102 room `R0` is adjacent to unknown room `R9`\nfound 1 error\n"
    code, result = json_result(capsys, "lint", str(tmp_path / "a"))
    assert result["files"] == [str(tmp_path / "a" / "b" / "two.lay"), str(tmp_path / "a" / "one.lay")]
    (tmp_path / "a" / "b" / "two.lay").write_text(GOOD.replace("R0 R1 0.9", "R0 R1 .9"))
    code, out, err = run_main(capsys, "fmt", "--check", str(tmp_path / "a"))
    assert code == 1 and err == f"would reformat {tmp_path / 'a' / 'b' / 'two.lay'}\n"
    assert out == "1 file would reformat, 1 already canonical\n"
    code, out, err = run_main(capsys, "fmt", "--write", str(tmp_path / "a"))
    assert code == 0 and run_main(capsys, "fmt", "--check", str(tmp_path / "a"))[0] == 0


def test_a_folder_without_specs_is_an_io_error(tmp_path, capsys):
    code, out, err = run_main(capsys, "lint", str(tmp_path))
    assert code == 2 and err == f"layoutdsl lint: error: no `.lay` files under `{tmp_path}`\n"


def test_the_specs_folder_lints_clean(capsys):
    code, out, _ = run_main(capsys, "lint", str(ROOT / "specs"))
    assert (code, out) == (0, "no problems found\n")


# ----------------------------------------------------------------- help


def help_text(name: str) -> str:
    """`layoutdsl NAME --help` as a 300-column terminal gets it (argparse reads COLUMNS)."""
    saved = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = "300"  # a wide terminal must not give 300-character lines
    try:
        return subparser(name).format_help()
    finally:
        if saved is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = saved


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_help_is_wrapped_with_examples_and_only_the_exit_codes_a_command_returns(name):
    text = help_text(name)
    longest = max(text.splitlines(), key=len)
    assert len(longest) <= 100, longest
    assert "\nexamples:\n  " in text, name
    listed = [int(code) for code in re.findall(r"^  (\d)  ", text.split("exit codes:")[1], re.M)]
    assert listed == list(exitcodes.BY_COMMAND[name])


def test_lint_and_fmt_no_longer_list_exit_code_3():
    assert exitcodes.NO_LAYOUT not in exitcodes.BY_COMMAND["lint"]
    assert exitcodes.NO_LAYOUT not in exitcodes.BY_COMMAND["fmt"]
    assert "\n  3  " not in help_text("fmt")


def test_the_exit_codes_are_documented_in_one_place():
    assert set(exitcodes.MEANINGS) == {0, 1, 2, 3}
    assert set(COMMANDS) <= set(exitcodes.BY_COMMAND)
    block = exitcodes.epilog((0, 2), "lint")
    assert block == "exit codes:\n  0  OK (warnings allowed)\n  2  usage, I/O or internal error (nothing was written)\n"


# ----------------------------------------------------------------- colour


def run_on_terminal(argv: list[str], env_extra: dict[str, str]) -> str:
    """Run layoutdsl with stdout and stderr on a pseudo-terminal; what it printed."""
    import pty

    master, slave = pty.openpty()
    env = {k: v for k, v in os.environ.items() if k != "NO_COLOR"}
    env.update(TERM="xterm", **env_extra)
    process = subprocess.Popen([sys.executable, "-m", "layoutdsl", *argv], stdout=slave, stderr=slave,
                               cwd=DIAGNOSTICS, env=env)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:  # the terminal closed: the command is done
            break
        if not data:
            break
        chunks.append(data)
    process.wait(timeout=60)
    os.close(master)
    return b"".join(chunks).decode()


def test_diagnostics_are_coloured_on_a_terminal_only():
    argv = ["lint", "E102_unknown_adjacent_room.lay"]
    coloured = run_on_terminal(argv, {})
    assert "\x1b[1;31merror[E102]\x1b[0m" in coloured
    assert ANSI.sub("", coloured).replace("\r\n", "\n") == (DIAGNOSTICS / "E102_unknown_adjacent_room.txt").read_text().replace("exit code: 1\n", "")
    assert ANSI.search(run_on_terminal(argv, {"NO_COLOR": "1"})) is None
    piped = subprocess.run([sys.executable, "-m", "layoutdsl", *argv], capture_output=True, text=True,
                           cwd=DIAGNOSTICS, env=dict(os.environ, TERM="xterm"))
    assert ANSI.search(piped.stdout + piped.stderr) is None


def test_error_lines_are_coloured_on_a_terminal_too(tmp_path):
    text = run_on_terminal(["compile", str(tmp_path / "nope.lay"), "-o", str(tmp_path)], {})
    assert "layoutdsl compile: \x1b[1;31merror\x1b[0m: cannot read" in text


# ----------------------------------------------------------------- variant names


def test_compile_and_batch_name_variants_the_same_way(tmp_path):
    from layoutdsl.batch import SolveLimits, plan_jobs
    from layoutdsl.cli.compile import variant_stem

    jobs = plan_jobs([str(TINY)], 2, base_seed=0, limits=SolveLimits(), formats=("xml",), timeout=60)
    assert [job.building for job in jobs] == [variant_stem("tiny", 1), variant_stem("tiny", 2)] == ["tiny-v1", "tiny-v2"]


def test_a_failed_variant_says_why(tmp_path, capsys, monkeypatch):
    from layoutdsl.compile import variants

    real = variants.compile_variants

    def second_fails(spec, n, **kwargs):
        result = real(spec, 1, **{**kwargs, "outdir": None})
        return variants.VariantsResult([result.layouts[0], None], [result.seeds[0], None], None, [], [None, None],
                                       [True, False], ())

    monkeypatch.setattr(variants, "compile_variants", second_fails)
    code, out, _ = run_main(capsys, "compile", str(TINY), "-o", str(tmp_path), "--variants", "2", "--emit", "xml",
                            "--node-limit", "5", "--time-limit", "7")
    assert code == exitcodes.NO_LAYOUT
    line = next(line for line in out.splitlines() if line.startswith("  tiny-v2"))
    assert line.startswith("  tiny-v2: no layout: no seed tried gave a new arrangement: for each, the generator")
    # a seed's try ends at the generator's work limits or the clock: the line names both
    assert "within its work limits or the time limit (7 s)" in line and "--time-limit" in line


# ----------------------------------------------------------------- deprecations


def test_import_no_hints_warns_that_it_does_nothing_and_goes_in_0_3(tmp_path, capsys):
    code, out, err = run_main(capsys, "import", str(PLAN), "-o", str(tmp_path / "p.lay"), "--no-hints", "-q")
    assert code == 0
    assert err == ("layoutdsl import: warning: `--no-hints` is deprecated and does nothing: a spec gets no "
                   "hints unless --keep-arrangement is given (the default since 0.1.0); the flag will be "
                   "removed in 0.3\n")
    assert "\nhints\n" not in (tmp_path / "p.lay").read_text()


def test_format_full_still_works_with_a_warning(capsys):
    code, out, err = run_main(capsys, "lint", "--format", "full", str(DIAGNOSTICS / "E005_expected_number.lay"))
    assert code == 1 and "error[E005]" in out
    assert "`--format full` is deprecated" in err and "--format text" in err


# ----------------------------------------------------------------- wrong kind of file


def test_compile_of_a_plan_says_to_import_it(tmp_path, capsys):
    code, _, err = run_main(capsys, "compile", str(PLAN), "-o", str(tmp_path / "out"))
    assert code == 1
    assert err.startswith("error[E019]: this is a building XML plan, not a layoutdsl spec\n")
    assert f"help: run `layoutdsl import {PLAN} -o school_Lamuniere1.lay`" in err
    assert "E002" not in err


def test_import_of_a_spec_says_it_is_a_spec(tmp_path, capsys):
    spec = ROOT / "specs" / "office_small.lay"
    code, _, err = run_main(capsys, "import", str(spec), "-o", str(tmp_path / "x.lay"))
    assert code == 1 and not (tmp_path / "x.lay").exists()
    assert err.startswith("error[E019]: this is a layoutdsl spec, not a plan to import\n")
    assert "malformed XML" not in err and f"layoutdsl compile {spec} -o out" in err


def test_evaluate_of_a_spec_says_it_is_not_a_plan(tmp_path, capsys):
    spec = ROOT / "specs" / "office_small.lay"
    code, _, err = run_main(capsys, "evaluate", str(PLAN), str(spec), "-o", str(tmp_path / "r"))
    assert code == 1 and not (tmp_path / "r").exists()
    assert err.startswith("error[E019]: this is a layoutdsl spec, not a building plan\n")
    assert "malformed XML" not in err


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_help_examples_parse(name):
    """Every `$ layoutdsl ...` line of a command's help is accepted by its parser, so the
    examples cannot drift from the flags."""
    import shlex

    examples = [line.split("$ ", 1)[1] for line in subparser(name).epilog.splitlines() if line.startswith("  $ ")]
    assert examples, name
    for example in examples:
        words = shlex.split(example)
        for stop in ("<", ">", "|"):
            if stop in words:
                words = words[:words.index(stop)]
        assert words[:2] == ["layoutdsl", name], example
        build_parser(name).parse_args(words[1:])  # SystemExit (a test error) if a flag is wrong


def test_an_internal_error_still_gives_a_json_result(monkeypatch, capsys):
    from layoutdsl.cli import lint

    def broken(_args):
        raise RuntimeError("boom")

    monkeypatch.delenv("LAYOUTDSL_TRACEBACK", raising=False)
    monkeypatch.setattr(lint, "run", broken)
    code, out, err = run_main(capsys, "lint", "specs/office_small.lay", "--format", "json")
    result = json.loads(out)
    assert code == 2 and result["status"] == "usage_or_io_error"
    assert result["errors"] == [{"kind": "internal", "message": "RuntimeError: boom"}]
    assert "internal error: RuntimeError: boom" in err


def test_a_usage_error_still_gives_a_json_result(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["compile", "specs/office_small.lay", "--format", "json", "--seed", "minus-one"])
    captured = capsys.readouterr()
    result = json.loads(captured.out)
    assert stop.value.code == 2 and result["status"] == "usage_or_io_error" and result["exit_code"] == 2
    assert "--seed" in result["errors"][0]["message"] and result["errors"][0]["kind"] == "usage"
    assert "usage: layoutdsl compile" in captured.err  # the usage still reaches the terminal


def test_when_no_variant_is_found_compile_points_at_the_single_compile(tmp_path, capsys, monkeypatch):
    from layoutdsl.compile import variants

    def none_found(spec, n, **kwargs):
        return variants.VariantsResult([None] * n, [None] * n, None, [], [None] * n, [False] * n, ())

    monkeypatch.setattr(variants, "compile_variants", none_found)
    code, out, _ = run_main(capsys, "compile", str(TINY), "-o", str(tmp_path), "--variants", "2", "--time-limit", "5")
    assert code == exitcodes.NO_LAYOUT
    assert out.count(": no layout: no seed tried gave a new arrangement") == 2
    assert f"none found: `layoutdsl compile {TINY} -o {tmp_path}` without --variants says whether" in out
    assert not list(tmp_path.iterdir())  # nothing written
