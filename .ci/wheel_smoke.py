#!/usr/bin/env python3
"""The package as installed is the package tested (issue 22).

Builds the wheel, installs it (with its dependencies and the ``dask`` and ``bench`` extras, so
every command has what it needs) in a fresh virtual environment, and runs every command of
README.md's ``## Commands`` block from a temporary directory outside the repository, as a user
who typed them would. The commands are read from README.md itself, so README and this test
cannot drift apart: a command added to README is run here, and a row of SHORTER or CLAIMS
naming a command README no longer has fails the test.

Where README says a command takes minutes or hours, SHORTER runs the same command with a
shorter budget through flags that exist (same code path, less work); every such substitution
is printed beside the command. A command passes when it exits 0 within its time limit and
what README claims about its result holds (CLAIMS: a plan solves, a file is written, the
output is JSON).

Usage: ``python .ci/wheel_smoke.py [--keep] [--only TEXT] [--venv DIR]``; exit 0 when every
command passes (``--venv``: a venv this script made and kept, to try the commands again without
building and installing).
Standard library only: it runs before, and outside, any environment of the project.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
EXTRAS = "dask,bench"  # the Dask executor's and `bench --agreement`'s peers (README names both)
LIMIT = 900.0  # s: a command still running after this fails (a hang must not hold CI)
SCHEDULER = "tcp://host:8786"  # README's placeholder, replaced by the local scheduler started here
DASK_NOTE = "a local scheduler and 2 workers started here; my.yaml is written (CONFIGS)"

# README command -> (the command run instead, why). Same code path, smaller budget, by flags
# the commands have. Each key must be a command of README's block (checked).
SHORTER: dict[str, tuple[str, str]] = {
    "partfeeder run paper --out sweep/paper": (
        "partfeeder run paper --out sweep/paper --designs 2",
        "hours: the paper's config on 2 of its 1000 designs",
    ),
    "partfeeder stress --cases 10000 --workers 2 --out stress": (
        "partfeeder stress --cases 30 --workers 2 --out stress",
        "~30 min: 30 of the 10,000 cases",
    ),
    "partfeeder bench --out bench-out": (
        "partfeeder bench --quick --out bench-out",
        "~3 min: the quick suite, written to the same files (CI well under 30 minutes)",
    ),
    "partfeeder planners --quick --out planners-quick": (
        "partfeeder planners --quick --runs 1 --out planners-quick",
        "~5 min: the quick suite with 1 run per planner and problem (of 3)",
    ),
    "partfeeder bench --agreement --out agree": (
        "partfeeder bench --agreement --out agree --design table3 --trials 3",
        "~6 min: one design, 3 trials per entry",
    ),
    "partfeeder optimize --from sweep/default": (
        "partfeeder optimize --from sweep/default --evaluations 32 --trials 20",
        "~3 min: 32 evaluations, 20 final trials (its budget flags; its own default --out)",
    ),
    "partfeeder optimize robust --from sweep/default": (
        "partfeeder optimize robust --from sweep/default --evaluations 2 --trials 20",
        "~5 min: 2 margins evaluations, 20 final trials",
    ),
    "partfeeder optimize --from sweep/default --evaluations 100 --trials 40": (
        "partfeeder optimize --from sweep/default --evaluations 32 --trials 20",
        "the optimize command above run again in the same folder: it resumes (issue 39: its "
        "output folder optimize/ had shadowed the shipped config 'optimize')",
    ),
    "partfeeder calibrate --part --out calibration": (
        "partfeeder calibrate --part --quick --out calibration",
        "~25 min: the quick grid",
    ),
    "partfeeder feasibility --designs 500 --levels kinematic,geometric --out feas": (
        "partfeeder feasibility --designs 6 --levels kinematic,geometric --out feas",
        "minutes: 6 of the 500 designs",
    ),
    "partfeeder bench --verdict": (
        "partfeeder bench --verdict 20",
        "~1 min: 20 of the 200 designs",
    ),
    "partfeeder run fig1-cup": (
        "partfeeder run fig1-cup --designs 24",
        "~4.5 min: 24 of the 1000 designs",
    ),
    "partfeeder optimize fig1-cup-optimize --from sweep/fig1-cup": (
        "partfeeder optimize fig1-cup-optimize --from sweep/fig1-cup --evaluations 16 --trials 10",
        "~6 min: 16 evaluations, 10 final trials",
    ),
    "partfeeder bench --part": (
        "partfeeder bench --part 5",
        "~20 s: 5 of the 50 trials",
    ),
}

# Configs written into the working directory: name -> (the shipped config it is made from,
# [(line pattern, replacement)], each pattern matching exactly one line). `my.yaml` is README's
# own config of the Dask example.
CONFIGS: dict[str, tuple[str, list[tuple[str, str]]]] = {
    "my.yaml": (
        "default.yaml",
        [(r"^name: default$", "name: my"), (r"^designs: \{count: \d+", "designs: {count: 4")],
    ),
}


@dataclass
class Outcome:
    """One command's row of the table."""

    readme: str
    ran: str
    status: int | None  # None: killed at LIMIT
    seconds: float
    problems: list[str]

    @property
    def passed(self) -> bool:
        return self.status == 0 and not self.problems


def readme_commands(text: str) -> list[str]:
    """The commands of README's ``## Commands`` block, comments stripped, in order."""
    section = text.split("\n## Commands\n", 1)
    if len(section) != 2:
        raise SystemExit("wheel smoke: README.md has no '## Commands' section")
    block = re.search(r"```bash\n(.*?)```", section[1], re.S)
    if block is None:
        raise SystemExit("wheel smoke: README.md's Commands section has no ```bash block")
    commands = [shlex.join(shlex.split(line, comments=True)) for line in block[1].splitlines()]
    return [c for c in commands if c]


# --- what README claims about each command's result ----------------------------------------

Check = Callable[[str, Path], list[str]]


def files(*names: str) -> Check:
    """Every path (a glob, relative to the working directory) matches at least one file."""

    def check(_out: str, work: Path) -> list[str]:
        return [f"{n} not written" for n in names if not any(work.glob(n))]

    return check


def is_json(out: str, _work: Path) -> list[str]:
    try:
        json.loads(out)
    except ValueError as exc:
        return [f"stdout is not JSON ({exc})"]
    return []


def plan_solved(out: str, _work: Path) -> list[str]:
    """Every orientation row of plan's table says solved (README: the paper's working design)."""
    rows = re.findall(r"^(heavy_\w+)\s+(yes|no)\s", out, re.M)
    if not rows:
        return ["no orientation rows in plan's table"]
    return [f"{o} not solved" for o, solved in rows if solved != "yes"]


def plan_json_solved(out: str, work: Path) -> list[str]:
    problems = is_json(out, work)
    if problems:
        return problems
    runs = json.loads(out)["runs"]
    return [f"{r['orientation']} not solved" for r in runs if not r["solved"]] or (
        [] if runs else ["no runs"]
    )


def contains(pattern: str) -> Check:
    def check(out: str, _work: Path) -> list[str]:
        return [] if re.search(pattern, out, re.M) else [f"output lacks /{pattern}/"]

    return check


def both(*checks: Check) -> Check:
    def check(out: str, work: Path) -> list[str]:
        return [p for c in checks for p in c(out, work)]

    return check


def overlay_unless_the_baseline(folder: str) -> Check:
    """The optimum drawn over the baseline, unless the summary says the optimum is the
    baseline itself: then no outline is drawn over itself (issue 39)."""

    def check(out: str, work: Path) -> list[str]:
        overlays = list(work.glob(f"{folder}/figures/overlay_*.png"))
        if re.search(r"^the optimum is the baseline, ", out, re.M):
            return [f"{o} draws the baseline over itself" for o in overlays]
        return [] if overlays else [f"{folder}/figures/overlay_*.png not written"]

    return check


SWEEP = ("report.html", "figures/*.png", "results.sqlite", "summary.json", "ompl/benchmark.db")
CLAIMS: dict[str, Check] = {
    # README: the report opens with the design to build, and gives its margins
    "partfeeder run": both(
        files(*(f"sweep/default/{f}" for f in SWEEP), "sweep/default/figures/margins.png"),
        contains(r"^recommended: "),
    ),
    "partfeeder run paper --out sweep/paper": files("sweep/paper/summary.json"),
    f"partfeeder run my.yaml --executor dask --scheduler {SCHEDULER}": files(
        "sweep/my/summary.json", "sweep/my/ompl/benchmark.db"
    ),
    "partfeeder report sweep/default": files("sweep/default/report.html"),
    "partfeeder optimize --from sweep/default": both(
        files("optimize/optimize/evaluations.sqlite", "optimize/optimize/report.html"),
        overlay_unless_the_baseline("optimize/optimize"),
    ),
    "partfeeder bench --trial": contains(r"trial"),
    "partfeeder optimize --from sweep/default --evaluations 100 --trials 40": contains(
        r"^optimisation optimize: \d+ designs evaluated"
    ),
    "partfeeder calibrate --part --out calibration": files("calibration/part-calibration.md"),
    "partfeeder run fig1-cup": files(*(f"sweep/fig1-cup/{f}" for f in SWEEP)),
    "partfeeder optimize fig1-cup-optimize --from sweep/fig1-cup": files(
        "optimize/fig1-cup-optimize/evaluations.sqlite",
        "optimize/fig1-cup-optimize/figures/strip_design_*.png",
    ),
    "partfeeder bench --part": contains(r"^cup / peg: "),
    "partfeeder margins --family fig1-cup --values "
    "0.6907,1.2855,1.2213,1.8129,1.1795,0.5437,0.1447,0.4392": contains(r"^pin_dy "),
    "partfeeder bench --verdict": contains(r"^  wilson / screen \+ sprt: "),
    "partfeeder simulate --family fig1 --samples 40": contains(r"^open_trailing "),
    "partfeeder run --json": is_json,
    "partfeeder plan --design table3 --orientation both --time 5 --seed 1 --out out": both(
        plan_solved, files("out/*.png")
    ),
    "partfeeder simulate --design table3 --orientation both --out drop": files(
        "drop/*.png", "drop/*.gif", "drop/*.json"
    ),
    "partfeeder simulate --design table3 --samples 200": contains(r"\bWORKS\b"),
    "partfeeder draw --design fig7a --out fig7a.png": files("fig7a.png"),
    "partfeeder bench --out bench-out": files(
        "bench-out/bench.json", "bench-out/summary.md", "bench-out/perf-*.png"
    ),
    "partfeeder bench --agreement --out agree": files(
        "agree/agreement.json", "agree/agreement.md", "agree/*.png"
    ),
    "partfeeder planners --quick --out planners-quick": files(
        "planners-quick/report.html",
        "planners-quick/report.json",
        "planners-quick/figures/*.png",
        "planners-quick/ompl/benchmark.db",
    ),
    "partfeeder feasibility --designs 500 --levels kinematic,geometric --out feas": files(
        "feas/*.json", "feas/*.csv"
    ),
}


def claim_of(readme: str) -> Check | None:
    """The claim for a README command. Every plan of README is of the paper's working design
    (table3, by name, scene or values) and must solve."""
    if readme in CLAIMS:
        return CLAIMS[readme]
    words = readme.split()
    if words[1:2] == ["plan"]:
        return plan_json_solved if "--json" in words else plan_solved
    if words[1:2] == ["stress"] and "--replay" in words:
        return contains("^same record as stored$")
    return None


# --- the environment ------------------------------------------------------------------------


def run(argv: list[str], **kwargs) -> None:
    print("+", shlex.join(argv), flush=True)
    subprocess.run(argv, check=True, stdin=subprocess.DEVNULL, **kwargs)


def build_and_install(tmp: Path) -> Path:
    """The wheel built from the repository, installed in a fresh venv; returns its bin dir."""
    dist = tmp / "dist"
    run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(dist), str(ROOT)])
    (wheel,) = dist.glob("partfeeder-*.whl")
    venv = tmp / "venv"
    run([sys.executable, "-m", "venv", str(venv)])
    bin_dir = venv / "bin"
    run([str(bin_dir / "python"), "-m", "pip", "install", "-q", f"{wheel}[{EXTRAS}]"])
    return bin_dir


def environment(bin_dir: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["PATH"] = f"{bin_dir}{os.pathsep}{env.get('PATH', '')}"
    env["VIRTUAL_ENV"] = str(bin_dir.parent)
    env["MPLBACKEND"] = "Agg"
    return env


def check_installed(bin_dir: Path, work: Path, env: dict[str, str]) -> None:
    """The commands must import the installed package, never the repository's source."""
    out = subprocess.run(
        [str(bin_dir / "python"), "-c", "import experiments; print(experiments.__file__)"],
        cwd=work,
        env=env,
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    if not Path(out).resolve().is_relative_to(bin_dir.parent.resolve()):
        raise SystemExit(f"wheel smoke: experiments imported from {out}, not the venv")
    print(f"installed package: {out}")


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def start_dask(
    bin_dir: Path, work: Path, env: dict[str, str], procs: list[subprocess.Popen]
) -> str:
    """A local scheduler and two one-thread workers (the package installed in them), added to
    ``procs`` as they start (each its own process group); returns the scheduler's address."""
    address = f"tcp://127.0.0.1:{free_port()}"
    log = (work / "dask.log").open("ab")
    dask = str(bin_dir / "dask")

    def start(*argv: str) -> subprocess.Popen:
        return subprocess.Popen(
            [dask, *argv, "--no-dashboard"],
            cwd=work,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )

    port = address.rsplit(":", 1)[1]
    procs.append(start("scheduler", "--host", "127.0.0.1", "--port", port))
    procs.append(start("worker", address, "--nworkers", "2", "--nthreads", "1"))
    wait = (
        "from distributed import Client\n"
        f"with Client({address!r}, timeout=60) as c: c.wait_for_workers(2, timeout=120)\n"
    )
    subprocess.run(
        [str(bin_dir / "python"), "-c", wait],
        cwd=work,
        env=env,
        stdin=subprocess.DEVNULL,
        check=True,
        timeout=200,
    )
    print(f"dask scheduler {address} with 2 workers (log: {log.name})")
    return address


def stop(procs: list[subprocess.Popen]) -> None:
    """End the process groups this script started (scheduler and workers), and only those."""
    for p in procs:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGTERM)
    for p in procs:
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()


def write_configs(work: Path) -> None:
    """The files of CONFIGS, from the configs the wheel ships."""
    for name, (source, edits) in CONFIGS.items():
        text = (ROOT / "experiments/configs" / source).read_text()
        for pattern, replacement in edits:
            text, n = re.subn(pattern, replacement, text, flags=re.M)
            if n != 1:
                raise SystemExit(f"wheel smoke: {source} has {n} lines like /{pattern}/, not 1")
        (work / name).write_text(text)


# --- the run -------------------------------------------------------------------------------


def run_command(readme: str, ran: str, work: Path, env: dict[str, str], logs: Path) -> Outcome:
    index = len(list(logs.glob("*.out")))
    out_file, err_file = logs / f"{index:02d}.out", logs / f"{index:02d}.err"
    print(f"\n$ {ran}", flush=True)
    start = time.perf_counter()
    with out_file.open("wb") as out, err_file.open("wb") as err:
        proc = subprocess.Popen(
            shlex.split(ran),
            cwd=work,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=out,
            stderr=err,
            start_new_session=True,
        )
        try:
            status: int | None = proc.wait(timeout=LIMIT)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            status = None
    seconds = time.perf_counter() - start
    stdout = out_file.read_text(errors="replace")
    problems = [] if status is not None else [f"still running after {LIMIT:.0f} s"]
    check = claim_of(readme)
    if status == 0 and check is not None:
        problems += check(stdout, work)
    outcome = Outcome(readme, ran, status, seconds, problems)
    print(stdout[-3000:], end="")
    if not outcome.passed:
        print(err_file.read_text(errors="replace")[-3000:], end="")
    print(f"[{'pass' if outcome.passed else 'FAIL'}: exit {status}, {seconds:.1f} s]", flush=True)
    return outcome


def table(outcomes: list[Outcome], total: float) -> str:
    width = max(len(o.ran) for o in outcomes)
    lines = [f"{'command as run':<{width}}  exit  seconds  result", "-" * (width + 25)]
    for o in outcomes:
        result = "pass" if o.passed else "FAIL: " + "; ".join(o.problems or ["exit status"])
        exit_text = "-" if o.status is None else str(o.status)
        lines.append(f"{o.ran:<{width}}  {exit_text:>4}  {o.seconds:7.1f}  {result}")
    for o in outcomes:
        if o.ran != o.readme:
            why = SHORTER[o.readme][1] if o.readme in SHORTER else DASK_NOTE
            lines.append(f"  for README's `{o.readme}`: {why}")
    passed = sum(o.passed for o in outcomes)
    lines.append(f"{passed} of {len(outcomes)} passed; {total:.0f} s in all")
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--keep", action="store_true", help="keep the temporary directory")
    parser.add_argument("--only", default=None, help="run only README commands containing TEXT")
    parser.add_argument("--venv", type=Path, default=None, help="reuse a kept venv (no build)")
    args = parser.parse_args()
    commands = readme_commands(README.read_text())
    stale = [c for c in (*SHORTER, *CLAIMS) if c not in commands]
    if stale:
        print(f"wheel smoke: not in README's Commands block any more: {stale}", file=sys.stderr)
        return 1
    if args.only:
        commands = [c for c in commands if args.only in c]
    start = time.perf_counter()
    tmp = Path(tempfile.mkdtemp(prefix="partfeeder-smoke-"))
    work, logs = tmp / "work", tmp / "logs"
    work.mkdir()
    logs.mkdir()
    procs: list[subprocess.Popen] = []
    address = ""
    try:
        bin_dir = build_and_install(tmp) if args.venv is None else args.venv.resolve() / "bin"
        env = environment(bin_dir)
        check_installed(bin_dir, work, env)
        write_configs(work)
        outcomes = []
        for readme in commands:
            ran = SHORTER.get(readme, (readme, ""))[0]
            if SCHEDULER in ran:
                if not procs:
                    address = start_dask(bin_dir, work, env, procs)
                ran = ran.replace(SCHEDULER, address)
            outcomes.append(run_command(readme, ran, work, env, logs))
        print("\n" + table(outcomes, time.perf_counter() - start))
        return 0 if all(o.passed for o in outcomes) else 1
    finally:
        stop(procs)
        if args.keep:
            print(f"kept: {tmp}")
        else:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
