"""Noise proportional to the keypoint size (``discovery.relative_noise``): the size surface, the
scaled evaluator, and the workflow with ``relative_noise`` on a reduced dataset whose noise grows
with the keypoints (the coarse material and 9 training designs of test_discovery.py)."""
import numpy as np
import pytest

from stitchswitch.validation.discovery.evaluate import Evaluator
from stitchswitch.validation.discovery.fit import follow_branches, scan_values
from stitchswitch.validation.discovery.noise.proportional import (
    SIZE_FLOOR_MM,
    KeypointScale,
    ScaledEvaluator,
)
from stitchswitch.validation.discovery.space import ModelSpec
from stitchswitch.validation.discovery.synthetic import (
    START_MATERIAL,
    TRUE_MATERIAL,
    dataset_text,
)
from stitchswitch.validation.discovery.workflow import DiscoveryConfig, discover
from stitchswitch.validation.measured import QUANTITIES, parse_measurements

COARSE = dict(n_nodes=80, dr_max_mm=1.0)
TRUE = TRUE_MATERIAL.replace(**COARSE)
START = START_MATERIAL.replace(**COARSE)
TRAIN = dict(train_d=(30.0, 50.0, 70.0), train_fill=(0.7, 0.85, 1.0), n_val=5)


def _quadratic_sizes(designs):
    a = np.asarray(designs, dtype=float)
    d, p = a[:, 0], a[:, 1]
    base = 2.0 + 0.002 * d * d + 3.0 * p * d / 50.0
    return np.stack([base * k for k in (1.0, 0.5, 2.0, 1.5, 0.8)], axis=1)


def test_the_scale_is_the_size_surface_over_its_mean_and_floored():
    designs = [(d, p) for d in (20.0, 40.0, 60.0, 80.0) for p in (0.6, 0.8, 1.0)]
    sizes = _quadratic_sizes(designs)
    scale = KeypointScale.from_rows(designs, -sizes)           # the size of -y is |y|
    assert np.allclose(scale(designs), sizes / sizes.mean(axis=0))
    assert np.allclose(scale(designs).mean(axis=0), 1.0)
    new = [(35.0, 0.7), (90.0, 0.95)]                          # never measured: the surface
    assert np.allclose(scale.size_mm(new), _quadratic_sizes(new))
    flat = KeypointScale.from_rows(designs, np.zeros((len(designs), 5)) + 0.2)
    assert np.allclose(flat.size_mm(designs), SIZE_FLOOR_MM)   # no size below the floor


def test_scaled_residuals_of_proportional_noise_have_one_spread():
    """Noise with sigma proportional to the size: divided by the fitted scale, the small and the
    big keypoints' residuals spread alike (raw, the big ones spread several times more), and
    the spread is sigma at the mean size. The scale comes from the noisy rows themselves."""
    rng = np.random.default_rng(5)
    designs = [(float(d), float(p)) for d in np.linspace(20, 90, 15)
               for p in np.linspace(0.6, 1.0, 15)]
    clean = _quadratic_sizes(designs)
    sigma = 0.1 * clean.mean(axis=0)                           # sigma at the mean size
    noisy = clean + rng.normal(size=clean.shape) * sigma * clean / clean.mean(axis=0)
    scale = KeypointScale.from_rows(designs, noisy)
    raw, scaled = noisy - clean, (noisy - clean) / scale(designs)
    small = clean[:, 0] < np.median(clean[:, 0])
    ratio = lambda e: e[~small].std(axis=0) / e[small].std(axis=0)     # noqa: E731
    assert np.all(ratio(raw) > 2.0)
    assert np.all((ratio(scaled) > 0.8) & (ratio(scaled) < 1.25))
    assert np.allclose(scaled.std(axis=0) / sigma, 1.0, atol=0.1)


def test_the_scaled_evaluator_divides_every_keypoint_and_its_targets():
    designs = [(30.0, 0.7), (70.0, 1.0), (50.0, 0.85)]
    rows = np.array([[4.0, 12.0, 1.0, 20.0, 0.5], [9.0, 30.0, 2.0, 45.0, 1.0],
                     [6.0, 20.0, 1.5, 30.0, 0.8]])
    raw = Evaluator(targets=dict(zip(designs, rows)))
    ev = ScaledEvaluator(raw, KeypointScale.from_rows(designs, rows))
    s = ev.scale(designs)
    spec = ModelSpec(START).with_effect("hoop_bending")
    x = spec.extend(ModelSpec(START).encode(START), (2.0,))
    x2 = x.copy()
    x2[0] += 0.01
    assert np.allclose(ev.one(spec, x, designs), raw.one(spec, x, designs) / s)
    assert np.allclose(ev.to_mm(designs, ev.one(spec, x, designs)), raw.one(spec, x, designs))
    assert np.allclose(ev.perturbed(spec, x, [x2], designs)[0],
                       raw.perturbed(spec, x, [x2], designs)[0] / s)
    states = [raw.solution(spec, x, d) for d in designs]
    assert np.allclose(ev.from_states(spec, x2, designs, states),
                       raw.from_states(spec, x2, designs, states) / s)
    (kp0, _), (kp1, _) = ev.continued(spec, [x, x2], designs)
    (r0, _), (r1, _) = raw.continued(spec, [x, x2], designs)
    assert np.allclose(kp0, r0 / s) and np.allclose(kp1, r1 / s)
    for d, row in zip(designs, rows):
        assert np.allclose(ev.targets[d], row / ev.scale([d])[0])
    assert ev.calls == raw.calls and ev.branches is raw.branches
    # the branch following sees the scaled keypoints and the scaled rows alike: it runs
    xs = [spec.extend(ModelSpec(START).encode(START), v) for v in scan_values(spec, 2)]
    assert follow_branches(spec, ev, designs, xs) >= 0


def _proportional_data(source, values, seed, rel=0.05):
    """The reduced dataset with noise sigma_iq = rel * (mean size of q) * size_iq / mean size:
    about 5 % of each keypoint at the mean size, more on the big ones."""
    text = dataset_text(source, values, seed=seed, material=TRUE, noise=False, **TRAIN)
    head = [ln for ln in text.splitlines() if ln.startswith("#") or ln.startswith("sample_id")]
    clean = parse_measurements(text, "clean.csv")
    y = clean.keypoints()
    size = np.maximum(np.abs(y), 1.0)
    sigma = rel * size.mean(axis=0) * size / size.mean(axis=0)
    rng = np.random.default_rng(seed)
    noisy = np.round(np.maximum(y + rng.normal(size=y.shape) * sigma, 0.1), 2) + 0.0
    lines = [ln.replace("NO noise", f"noise proportional to the keypoint size, {rel:g} at the "
                                    "mean size") for ln in head]
    for r, k in zip(clean.rows, noisy):
        lines.append(f"{r.label},{r.diameter_mm:g},{r.fill:g}," + ",".join(f"{v:.2f}" for v in k)
                     + f",{r.split}")
    return parse_measurements("\n".join(lines) + "\n", f"{source}-proportional.csv"), clean


def test_the_workflow_fits_size_scaled_keypoints_and_reports_mm():
    """prestretch_loss hidden at 0.35 under proportional noise: named with ``relative_noise``,
    its gap to the noise-free truth shrinks, and what is reported per row is in mm."""
    data, clean = _proportional_data("prestretch_loss", (0.35,), 21)
    config = DiscoveryConfig(effects=("prestretch_loss", "hoop_bending", "fill_exponent"),
                             folds=3, fit_max_nfev=8, cv_max_nfev=2, scan_points=3,
                             permutations=300, seed=22, relative_noise=True)
    disc = discover(data, START, config)
    s = disc.summary
    assert s["missing_effect"] == "prestretch_loss"
    assert np.array_equal(disc.measured, data.keypoints())      # the rows back in mm
    va = disc.split == "val"
    y = clean.keypoints()
    gap = lambda pred: np.mean(np.abs(pred[va] - y[va]), axis=0)   # noqa: E731
    assert gap(disc.after)[1] < gap(disc.before)[1]
    mae = np.mean(np.abs(disc.before[va] - disc.measured[va]), axis=0)
    assert [s["before"][q]["mae_mm"] for q in QUANTITIES] == pytest.approx(mae)
    assert s["relative_noise"]["size_floor_mm"] == SIZE_FLOOR_MM
    assert "size" in s["noise_floor"]["how"] and s["config"]["relative_noise"] is True
    # the estimated noise floor is sigma at the mean size: 5 % of the mean size, within what
    # 9 training rows and a quadratic surface (3 degrees of freedom) can estimate
    mean = np.array([s["relative_noise"]["mean_size_mm"][q] for q in QUANTITIES])
    sigma = np.array([s["noise_floor"]["sigma_mm"][q] for q in QUANTITIES])
    assert np.all(sigma < 0.05 * mean * 3.0)
