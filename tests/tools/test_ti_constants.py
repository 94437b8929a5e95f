"""Tests of tools/ti_constants.py (camclay9.ti_constants) against independently known numbers (theory.md 4.3, Table 1 of
Yin, Liu & Borja 2021)."""

import json
import pathlib
import subprocess
import sys

import numpy as np
import pytest
from camclay9 import ti_constants as ti

TOOL = pathlib.Path(__file__).resolve().parents[2] / "tools" / "ti_constants.py"

# Table 1, hard frame. "converted" is what the scenes use; "original" is the paper's engineering column.
CONVERTED = dict(lam=2900.0, muT=18000.0, muL=13000.0, a=4100.0, b=6900.0)
ORIGINAL = dict(Ep=38000.0, En=33000.0, nu_pp=0.038, nu_pn=0.19, Gnp=13000.0)


def test_table1_converted_inverts_to_the_verified_engineering_constants():
    r = ti.lame_to_engineering(**CONVERTED)
    # theory.md 4.3 [VER]
    assert r["Ep"] == pytest.approx(37402, abs=1.0)
    assert r["En"] == pytest.approx(31655, abs=1.0)
    assert r["nu_pp"] == pytest.approx(0.0389, abs=5e-5)
    assert r["Gnp"] == pytest.approx(13000, abs=1e-9)
    assert r["Gpp"] == pytest.approx(18000, abs=1e-9)
    assert r["S13"] == pytest.approx(-5.290e-6, abs=5e-10)
    assert r["nu_pn"] == pytest.approx(0.1979, abs=5e-5)   # S13 = -nu/Ep reading
    assert r["nu_np"] == pytest.approx(0.1675, abs=5e-5)   # S13 = -nu/En reading
    # Mandel eigenvalues quoted in theory.md 4.3
    assert r["mandel_eigenvalues"] == pytest.approx([26000, 26000, 27260, 36000, 36000, 48540], abs=1.0)


def test_table1_converted_within_5_percent_of_the_original_column():
    r = ti.lame_to_engineering(**CONVERTED)
    for key in ORIGINAL:
        assert r[key] == pytest.approx(ORIGINAL[key], rel=0.05), key


def test_forward_conversion_of_the_original_column():
    # theory.md 4.3: S13 = -0.19/Ep gives (2823, 18304, 13000, 4149, 8789)
    r = ti.engineering_to_lame(**ORIGINAL)
    expected = dict(lam=2823, muT=18304, muL=13000, a=4149, b=8789)
    for key, value in expected.items():
        assert abs(r[key] - value) < 1.0, (key, r[key])


def test_forward_stiffness_matches_numerical_inversion_of_the_compliance():
    e = ORIGINAL
    S = np.zeros((6, 6))
    S[0, 0] = S[1, 1] = 1 / e["Ep"]
    S[0, 1] = S[1, 0] = -e["nu_pp"] / e["Ep"]
    S[0, 2] = S[2, 0] = S[1, 2] = S[2, 1] = -e["nu_pn"] / e["Ep"]
    S[2, 2] = 1 / e["En"]
    S[3, 3] = 2 * (1 + e["nu_pp"]) / e["Ep"]
    S[4, 4] = S[5, 5] = 1 / e["Gnp"]
    r = ti.engineering_to_lame(**e)
    C = ti.stiffness_bedding_axes(r["lam"], r["muT"], r["muL"], r["a"], r["b"])
    np.testing.assert_allclose(C, np.linalg.inv(S), rtol=1e-12, atol=1e-8)


def test_isotropic_soft_frame():
    r = ti.isotropic_to_lame(E=8000.0, nu=0.3)
    assert r["lam"] == pytest.approx(4615.4, abs=0.05)
    assert r["mu"] == pytest.approx(3076.9, abs=0.05)


@pytest.mark.parametrize("lame", [
    CONVERTED,
    dict(lam=2823.112, muT=18304.43, muL=13000.0, a=4148.98, b=8788.59),
    dict(lam=-500.0, muT=1000.0, muL=3000.0, a=-200.0, b=-1500.0),
    dict(lam=4600.0, muT=3100.0, muL=3100.0, a=0.0, b=0.0),
])
def test_round_trip_is_identity(lame):
    e = ti.lame_to_engineering(**lame)
    back = ti.engineering_to_lame(e["Ep"], e["En"], e["nu_pp"], e["nu_pn"], e["Gnp"])
    for key, value in lame.items():
        assert abs(back[key] - value) <= 1e-10 * max(1.0, abs(value)), (key, back[key], value)
    # and the other way round
    e2 = ti.lame_to_engineering(back["lam"], back["muT"], back["muL"], back["a"], back["b"])
    for key in ("Ep", "En", "nu_pp", "nu_pn", "Gnp"):
        assert e2[key] == pytest.approx(e[key], rel=1e-10)


def test_isotropic_engineering_set_gives_a_b_zero():
    E, nu = 8000.0, 0.3
    r = ti.engineering_to_lame(Ep=E, En=E, nu_pp=nu, nu_pn=nu, Gnp=E / (2 * (1 + nu)))
    iso = ti.isotropic_to_lame(E, nu)
    assert abs(r["a"]) < 1e-9 * E
    assert abs(r["b"]) < 1e-9 * E
    assert r["muT"] == pytest.approx(r["muL"], rel=1e-12)
    assert r["lam"] == pytest.approx(iso["lam"], rel=1e-12)
    assert r["muT"] == pytest.approx(iso["mu"], rel=1e-12)


@pytest.mark.parametrize("kwargs, option", [
    (dict(ORIGINAL, nu_pp=1.2), "--nu-pp"),
    (dict(ORIGINAL, Ep=-1.0), "--Ep"),
    (dict(ORIGINAL, En=0.0), "--En"),
    (dict(ORIGINAL, Gnp=0.0), "--Gnp"),
    (dict(ORIGINAL, nu_pn=0.8), "--nu-pn"),
    (dict(ORIGINAL, nu_pn=float("nan")), "--nu-pn"),
])
def test_bad_engineering_input_names_the_option(kwargs, option):
    with pytest.raises(ti.InputError) as info:
        ti.engineering_to_lame(**kwargs)
    assert info.value.option == option
    assert option in str(info.value)


@pytest.mark.parametrize("kwargs, option", [
    (dict(CONVERTED, muT=0.0), "--muT"),
    (dict(CONVERTED, muL=-5.0), "--muL"),
    (dict(CONVERTED, lam=-20000.0), "--lam"),
    (dict(CONVERTED, b=-30000.0), "--b"),
])
def test_non_positive_definite_stiffness_is_rejected(kwargs, option):
    with pytest.raises(ti.InputError) as info:
        ti.lame_to_engineering(**kwargs)
    assert info.value.option == option
    # the rejected set really is not positive definite
    C = ti.stiffness_bedding_axes(**kwargs)
    assert ti.mandel_eigenvalues(C)[0] <= 0.0


def test_b_bound_is_sharp():
    lam, muT, muL, a = 2900.0, 18000.0, 13000.0, 4100.0
    b_min = (lam + a) ** 2 / (lam + muT) - (lam - 2 * muT + 2 * a + 4 * muL)
    C = ti.stiffness_bedding_axes(lam, muT, muL, a, b_min)
    assert abs(ti.mandel_eigenvalues(C)[0]) < 1e-9
    ti.lame_to_engineering(lam, muT, muL, a, b_min + 1.0)          # accepted


def _run(*args):
    return subprocess.run([sys.executable, str(TOOL), *args], capture_output=True, text=True, timeout=600)


def test_cli():
    ok = _run("to-engineering", "--lam", "2900", "--muT", "18000", "--muL", "13000",
              "--a", "4100", "--b", "6900", "--json")
    assert ok.returncode == 0, ok.stderr
    r = json.loads(ok.stdout)
    assert r["Ep"] == pytest.approx(37402, abs=1.0)
    assert r["S13"] == pytest.approx(-5.290e-6, abs=5e-10)

    text = _run("to-lame", "--Ep", "38000", "--En", "33000", "--nu-pp", "0.038", "--nu-pn", "0.19",
                "--Gnp", "13000")
    assert text.returncode == 0, text.stderr
    props = next(l for l in text.stdout.splitlines() if l.startswith("PROPS 2-6:"))
    values = [float(v) for v in props.split(":", 1)[1].split(",")]
    assert values == pytest.approx([2823, 18304, 13000, 4149, 8789], abs=1.0)

    bad = _run("to-lame", "--Ep", "38000", "--En", "33000", "--nu-pp", "1.2", "--nu-pn", "0.19",
               "--Gnp", "13000")
    assert bad.returncode == 2
    assert "--nu-pp" in bad.stderr and "1.2" in bad.stderr and "< 1" in bad.stderr
    assert bad.stdout == ""
