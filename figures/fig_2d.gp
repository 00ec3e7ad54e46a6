# SPDX-License-Identifier: GPL-3.0-or-later
# Inelastic hard disks after Haff's law: the paper's d-dimensional prediction in d = 2
# (docs/dimensions.md), drawn by late_decay.gp.
dimension = 2
load styledir.'/late_decay.gp'
