# SPDX-License-Identifier: GPL-3.0-or-later
# Fig. 4 with sticky sub-threshold collisions for r = 0.5 and 0.9 (clusters merge
# below delta instead of colliding elastically), the paper's other mechanism,
# drawn by fig4.gp from this figure's own phi.dat: the same nine blocks, r = 0
# being Fig. 4's own run.
subtitle = ', sticky below δ'
rnames = '"r = 0" "r = 0.5, sticky below δ" "r = 0.9, sticky below δ"'
load styledir.'/fig4.gp'
