"""Every subprocess a test starts has a timeout (issue 38: a broken gap once hung a test's driver run for 20 min of
CPU). Scanned: the Python of tests/ and the scripts the tests run (tools/reproduce.py, input/calibrate/
make_synthetic.py, the package camclay9's launcher), and the benchmarks' and tools' own (bench/, tools/, post/): each subprocess.run/call/check_call/check_output names a
timeout, and each Popen's wait()/communicate() in that file does (or the Popen's owner kills it after a
deadline: reproduce.py's --job-timeout);
every execute_process of the CMake scripts under tests/ names a TIMEOUT. The scanner is checked on snippets without
them (it must find them)."""
import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = [ROOT / "tools" / "reproduce.py", ROOT / "input" / "calibrate" / "make_synthetic.py",
           *sorted((ROOT / "python" / "camclay9").glob("*.py")),  # the launcher the tests and benchmarks use
           *sorted((ROOT / "bench").glob("*.py")), *sorted((ROOT / "tools").rglob("*.py")),
           *sorted((ROOT / "post").rglob("*.py"))]
BOUNDED_POPEN = {"tools/reproduce.py": "Job.poll kills a run after --job-timeout (paper.reproduce_quick: 300 s)"}


def untimed_calls(source, name="<snippet>"):
    """The subprocess calls of a Python source without a timeout: (name, line, what)."""
    out, tree = [], ast.parse(source)
    for n in ast.walk(tree):
        if not isinstance(n, ast.Call) or not isinstance(n.func, ast.Attribute):
            continue
        kw = {k.arg for k in n.keywords}
        base = getattr(n.func.value, "id", "")
        if base == "subprocess" and n.func.attr in ("run", "call", "check_call", "check_output") and "timeout" not in kw:
            out.append((name, n.lineno, f"subprocess.{n.func.attr}"))
        if n.func.attr in ("wait", "communicate") and base != "subprocess" and not n.args and "timeout" not in kw \
                and "subprocess.Popen" in source and name not in BOUNDED_POPEN:
            out.append((name, n.lineno, f".{n.func.attr}()"))
    return out


def untimed_execute_process(text, name="<snippet>"):
    """The execute_process calls of a CMake script without a TIMEOUT: (name, line)."""
    out = []
    for m in re.finditer(r"execute_process\s*\(", text):
        depth, i = 1, m.end()
        while depth and i < len(text):
            depth += {"(": 1, ")": -1}.get(text[i], 0)
            i += 1
        if not re.search(r"\bTIMEOUT\b", text[m.end():i]):
            out.append((name, text[: m.start()].count("\n") + 1))
    return out


def test_scanner_finds_what_it_looks_for():
    py = "import subprocess\nsubprocess.run(['x'])\np = subprocess.Popen(['y'])\np.wait()\nsubprocess.run(['z'], timeout=5)\n"
    assert [w for _, _, w in untimed_calls(py)] == ["subprocess.run", ".wait()"]
    cm = "execute_process(COMMAND a RESULT_VARIABLE rc)\nexecute_process(COMMAND b TIMEOUT 9 RESULT_VARIABLE rc)\n"
    assert untimed_execute_process(cm) == [("<snippet>", 1)]


def test_every_test_subprocess_has_a_timeout():
    files = sorted((ROOT / "tests").rglob("*.py")) + SCRIPTS
    found = [c for f in files for c in untimed_calls(f.read_text(), str(f.relative_to(ROOT)))]
    assert not found, found
    for name, why in BOUNDED_POPEN.items():
        assert "self.timeout" in (ROOT / name).read_text(), (name, why)


def test_every_execute_process_has_a_timeout():
    files = sorted((ROOT / "tests").rglob("*.cmake"))
    found = [c for f in files for c in untimed_execute_process(f.read_text(), str(f.relative_to(ROOT)))]
    assert len(files) >= 5 and not found, found
