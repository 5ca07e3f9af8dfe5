"""sb3_hfo's command-line tools: ``train``, ``enjoy``, ``record_video`` (rl-zoo3's, with SkillDDPG registered),
``evaluate``, ``plot`` and ``models`` (the committed models' manifest).

Run them as ``python -m sb3_hfo.train ...`` (``sb3_hfo.train`` and its siblings are entry points that call
``sb3_hfo.cli.train.main``) or ``python -m sb3_hfo.cli.models list``. They need the ``[zoo]`` extra (rl-zoo3,
Optuna, matplotlib) and, for a window or a video, ``[render]``; the library (:mod:`sb3_hfo`,
:mod:`sb3_hfo.evaluation`, :mod:`sb3_hfo.models`) imports none of this package.
"""
