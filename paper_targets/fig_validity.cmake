# SPDX-License-Identifier: GPL-3.0-or-later
# The validity map of the threshold delta (docs/validity.md): when each
# observable of the delta > 0 gas leaves the sticky gas it stands in for.
shockgas_figure_runs(fig_validity)
