"""Launching the driver: where it is, its command line, and one run with a timeout.

`driver_path(name, root)`: the executable `name` ('driver', or 'driver_elastic' with the elastic UMAT): from the
environment ($DRIVER for 'driver', $DRIVER_ELASTIC for 'driver_elastic', else the sibling of $DRIVER), else
ROOT/build/bin/NAME, ROOT the repository (given, or `repo_root()`: the one of the script being run, else the one of
the current directory).

`run_measured(cmd, log)`: one command with its output to a file, and its own CPU and peak memory (wait4).

`run_driver(scene, out, options)`: runs `driver -input SCENE -output_dir OUT OPTIONS...` (on `ranks` MPI ranks
through mpiexec, after a `prefix` such as ["nice", "-n", "10"]), always with a timeout, and returns the
subprocess.CompletedProcess (text stdout and stderr) with its wall and CPU seconds as `.wall` and `.cpu`. With
check (the default) a failure raises DriverError naming the command, the exit code and the tail of stderr.
"""
import os
import re
import resource
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

MPIEXEC = ("mpiexec", "--allow-run-as-root", "--oversubscribe", "-n")
TAIL = 2000  # characters of stderr (and stdout) quoted in a DriverError


class DriverError(RuntimeError):
    """The driver failed, timed out or could not start: `command`, `returncode` (None: timed out), `stdout`,
    `stderr`."""

    def __init__(self, command, returncode, stdout, stderr, why):
        self.command, self.returncode, self.stdout, self.stderr = command, returncode, stdout or "", stderr or ""
        tail = self.stderr[-TAIL:] or self.stdout[-TAIL:] or "(no output)"
        super().__init__(f"{shlex.join(str(c) for c in command)}: {why}; the end of its "
                         f"{'stderr' if self.stderr else 'output'}:\n{tail}")


def repo_root(start=None):
    """The repository holding `start` (default: the one holding the script being run, so that a script of the
    repository finds its own wherever it is started, else the one holding the current directory: under pytest or
    python -m): the first folder upward with CMakeLists.txt and driver/src. FileNotFoundError when there is none."""
    starts = [Path(start)] if start else [Path(sys.argv[0] or ".").parent, Path(os.getcwd())]
    for here in (s.resolve() for s in starts):
        for d in (here, *here.parents):
            if (d / "CMakeLists.txt").is_file() and (d / "driver" / "src").is_dir():
                return d
    raise FileNotFoundError(f"{starts[-1].resolve()}: not inside the repository (no folder upward holds CMakeLists.txt "
                            f"and driver/src); give root= or set $DRIVER")


def driver_path(name="driver", root=None):
    """The driver executable `name` (see the module's docstring); FileNotFoundError naming where it was looked
    for when it is not there."""
    env = os.environ.get(name.upper())
    if env:
        path, how = Path(env), f"${name.upper()}"
    elif name != "driver" and os.environ.get("DRIVER"):
        path, how = Path(os.environ["DRIVER"]).parent / name, "beside $DRIVER"
    else:
        path, how = repo_root(root) / "build" / "bin" / name, "the build"
    if not (path.is_file() and os.access(path, os.X_OK)):
        raise FileNotFoundError(f"{path} ({how}): no such executable; build it (cmake -S . -B build && cmake --build "
                                f"build) or set ${name.upper()}")
    return path


def driver_command(scene, out=None, options=(), driver=None, name="driver", root=None, ranks=1, prefix=()):
    """The command line of one run: [mpiexec ... -n RANKS] [PREFIX...] DRIVER -input SCENE [-output_dir OUT]
    OPTIONS..."""
    exe = Path(driver) if driver else driver_path(name, root)
    cmd = [*prefix, str(exe), "-input", str(scene)]
    if out is not None:
        cmd += ["-output_dir", str(out)]
    cmd += [str(o) for o in options]
    return [*MPIEXEC, str(ranks), *cmd] if ranks > 1 else cmd


def _cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_command(cmd, timeout=3600, cwd=None, env=None, check=True):
    """Run a driver command line (driver_command's), output captured as text, within `timeout` seconds; the
    CompletedProcess with .wall and .cpu (seconds). DriverError when it cannot start, times out or (check)
    exits non-zero."""
    if not timeout or timeout <= 0:
        raise ValueError(f"timeout = {timeout!r}: expected a positive number of seconds")
    c0, t0 = _cpu_children(), time.perf_counter()
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, env=env, timeout=timeout)
    except subprocess.TimeoutExpired as err:
        out = err.stdout.decode(errors="replace") if isinstance(err.stdout, bytes) else err.stdout
        errs = err.stderr.decode(errors="replace") if isinstance(err.stderr, bytes) else err.stderr
        raise DriverError(cmd, None, out, errs, f"timed out after {timeout:g} s") from None
    except OSError as err:
        raise DriverError(cmd, None, "", str(err), "could not start") from None
    proc.wall, proc.cpu = time.perf_counter() - t0, _cpu_children() - c0
    if check and proc.returncode:
        raise DriverError(cmd, proc.returncode, proc.stdout, proc.stderr, f"exit code {proc.returncode}")
    return proc


def _tree_usage(pid):
    """A running process's CPU (user + system of it and of every descendant alive, each with the children it has
    waited for) and the largest peak resident memory among them [MB], from /proc (Linux)."""
    tick, parent, stat = os.sysconf("SC_CLK_TCK"), {}, {}
    for d in Path("/proc").iterdir():
        try:
            f = (d / "stat").read_text().rsplit(")", 1)[1].split()
            parent[int(d.name)], stat[int(d.name)] = int(f[1]), [int(x) for x in f[11:15]]
        except (ValueError, OSError, IndexError):
            continue
    tree, grew = {pid}, True
    while grew:
        new = {p for p, q in parent.items() if q in tree} - tree
        tree, grew = tree | new, bool(new)
    cpu = sum(sum(stat[p]) for p in tree if p in stat)   # each one's own and its waited-for children's (e.g. a rank's gmsh)
    hwm = 0
    for p in tree:
        try:
            hwm = max(hwm, int(re.search(r"VmHWM:\s+(\d+)", Path(f"/proc/{p}/status").read_text())[1]))
        except (OSError, TypeError):
            continue
    return cpu / tick, hwm / 1024


def run_measured(cmd, log, timeout=3600, cwd=None, budget=None):
    """Run a command line with its output (stdout and stderr) written to the file `log` as it runs, within `timeout`
    seconds, and measure that one process from wait4: its CPU (user + system, its waited-for children's included)
    and peak resident memory, which run_command's totals over all children cannot give. Returns (exit code, CPU s,
    peak MB, wall s); DriverError when it cannot start or times out (the process is killed). `budget` (s): after
    that long the process and its descendants (its own session) are stopped by SIGTERM, their CPU and peak memory
    read from /proc just before, and the exit code is -SIGTERM: for a run that writes checkpoints and is resumed later."""
    if not timeout or timeout <= 0:
        raise ValueError(f"timeout = {timeout!r}: expected a positive number of seconds")
    if budget is not None and budget <= 0:
        raise ValueError(f"budget = {budget!r}: expected a positive number of seconds")
    t0 = time.perf_counter()
    with open(log, "w") as f:
        try:
            proc = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=cwd, start_new_session=budget is not None)
        except OSError as err:
            raise DriverError(cmd, None, "", str(err), "could not start") from None
        while True:  # wait4 collects the process with its own resources; polled, for the timeout
            pid, status, ru = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if budget is not None and time.perf_counter() - t0 > budget:
                cpu, mb = _tree_usage(proc.pid)   # read before the stop: mpiexec does not pass its ranks' usage on
                os.killpg(proc.pid, signal.SIGTERM)   # its own session: the ranks too, whatever mpiexec passes on
                os.wait4(proc.pid, 0)
                return -signal.SIGTERM, cpu, mb, time.perf_counter() - t0
            if time.perf_counter() - t0 > timeout:
                proc.kill()
                os.wait4(proc.pid, 0)
                raise DriverError(cmd, None, Path(log).read_text(errors="replace"), "", f"timed out after {timeout:g} s")
            time.sleep(0.05)
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024, time.perf_counter() - t0


def run_driver(scene, out=None, options=(), *, driver=None, name="driver", root=None, ranks=1, prefix=(),
               timeout=3600, cwd=None, env=None, check=True):
    """One run of the driver on SCENE into OUT (see the module's docstring)."""
    cmd = driver_command(scene, out, options, driver=driver, name=name, root=root, ranks=ranks, prefix=prefix)
    return run_command(cmd, timeout=timeout, cwd=cwd, env=env, check=check)
