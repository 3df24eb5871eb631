"""Bayesian optimisation for failure search: the proposer behind ``search(strategy="bo")``.

Each generation, a Gaussian process (scikit-learn; Matérn 5/2 kernel with one length scale per
coordinate, plus noise) is fitted to the badness of every episode so far (lower is worse:
failures below successes, then by score) and the generation's points are the candidates with
the largest expected improvement over the worst episode so far, kept apart from each other.
Candidates: uniform points and small steps around the ten worst episodes. The first
generations (until there are 2 d + 2 episodes, at least 10) are uniform points. Deterministic
for a seed. See docs/search.md.
"""

import numpy as np

_MAX_TRAINING = 300      # the GP sees at most the 150 worst and the 150 latest episodes
_CANDIDATES = 2000       # uniform candidates per generation
_LOCAL_STEP = 0.05       # the spread of the candidates around the worst episodes
_MIN_SPACING = 0.05      # chosen points of one generation at least this far apart


def _initial_count(dimension):
    return max(10, 2 * dimension + 2)


def propose(X, y, count, dimension, seed, generation):
    """``count`` points of [0, 1)^dimension for the next generation, as lists of floats."""
    rng = np.random.default_rng([seed, generation, 0xB0])
    if len(X) < _initial_count(dimension):
        return rng.random((count, dimension)).tolist()
    # Imported here: only Bayesian optimisation needs scikit-learn.
    from scipy.special import ndtr
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import ConstantKernel, Matern, WhiteKernel
    import warnings

    X = np.asarray(X, dtype=float)
    y = np.asarray(y, dtype=float)
    # A failure's badness sits 1e9 below every success: squash the scale so the GP sees the
    # order and the score's shape, not the offset.
    y = np.sign(y) * np.log1p(np.abs(y))
    if len(X) > _MAX_TRAINING:
        worst = np.argsort(y)[:_MAX_TRAINING // 2]
        latest = np.arange(len(X) - _MAX_TRAINING // 2, len(X))
        keep = np.unique(np.concatenate([worst, latest]))
        X, y = X[keep], y[keep]
    kernel = (ConstantKernel(1.0, (1e-3, 1e3))
              * Matern(length_scale=np.full(dimension, 0.3), length_scale_bounds=(1e-2, 1e1),
                       nu=2.5)
              + WhiteKernel(1e-4, (1e-8, 1e-1)))
    gp = GaussianProcessRegressor(kernel=kernel, normalize_y=True, random_state=seed)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        gp.fit(X, y)
    worst = X[np.argsort(y)[:10]]
    local = worst[rng.integers(0, len(worst), _CANDIDATES // 2)]
    local = np.clip(local + rng.normal(0, _LOCAL_STEP, local.shape), 0, 1 - 1e-12)
    candidates = np.vstack([rng.random((_CANDIDATES, dimension)), local])
    mean, sd = gp.predict(candidates, return_std=True)
    best = y.min()
    sd = np.maximum(sd, 1e-12)
    z = (best - mean) / sd
    improvement = (best - mean) * ndtr(z) + sd * np.exp(-0.5 * z * z) / np.sqrt(2 * np.pi)
    chosen = []
    for i in np.argsort(-improvement):
        if all(np.linalg.norm(candidates[i] - candidates[j]) >= _MIN_SPACING for j in chosen):
            chosen.append(i)
        if len(chosen) == count:
            break
    while len(chosen) < count:  # too few far-apart candidates: fill with uniform points
        candidates = np.vstack([candidates, rng.random((1, dimension))])
        chosen.append(len(candidates) - 1)
    return candidates[chosen].tolist()
