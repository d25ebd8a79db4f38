"""Synthesis: find the linkage that does a job.

* :mod:`symlink.synthesis.quick_return` designs a quick-return crank-rocker exactly
  from its time ratio and stroke;
* :mod:`symlink.synthesis.function` generates a function (rocker angle against crank
  angle) with Freudenstein's equation: three Chebyshev precision points in closed form, or
  least squares over many points, verified over the range;
* :mod:`symlink.synthesis.path` puts a coupler point through N points, with or without
  timing, by least squares with the exact Jacobian of the closed form (SciPy, the
  ``synthesis`` extra), with constraints enforced;
* :mod:`symlink.synthesis.general` puts a named point of any one-input linkage (catalog
  entry, linkage file or joints; in closed form, or by Newton's method continued from an
  assembly) through N points, with or without timing,
  its free parameters within bounds and its placement free or fixed, by the exact
  Jacobian of the generated sensitivities, verified by the linkage's generated solver;
* :mod:`symlink.synthesis.motion` guides a coupler through given poses (motion
  generation by Burmester theory);
* :mod:`symlink.synthesis.general_function` and :mod:`symlink.synthesis.general_motion`
  generate a function (an output angle or travel against the input) and guide a link
  through poses for any one-input linkage, by the exact gradients
  of :mod:`symlink.synthesis.design_fit`;
* :mod:`symlink.synthesis.shape` matches a curve's shape alone (Fourier descriptors,
  similarity alignment); :mod:`symlink.synthesis.placement` writes a placed design
  as a linkage of its own (what ``symlink synthesize ... --out`` saves).
"""
