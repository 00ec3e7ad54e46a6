# SPDX-License-Identifier: GPL-3.0-or-later
# Inelastic hard spheres after Haff's law: the paper's d-dimensional prediction in d = 3
# (docs/dimensions.md), drawn by late_decay.gp.
dimension = 3
load styledir.'/late_decay.gp'
