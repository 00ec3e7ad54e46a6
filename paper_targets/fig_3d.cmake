# SPDX-License-Identifier: GPL-3.0-or-later
# The paper's d-dimensional prediction in d = 3 (docs/dimensions.md): late_decay.cmake.
include(${CMAKE_CURRENT_LIST_DIR}/late_decay.cmake)
shockgas_late_decay_figure(fig_3d)
