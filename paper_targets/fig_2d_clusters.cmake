# SPDX-License-Identifier: GPL-3.0-or-later
# Clusters of the 2D gas of fig_2d against N_c ~ eps^(-2d/(4-d)) (docs/dimensions.md): clusters.cmake.
include(${CMAKE_CURRENT_LIST_DIR}/clusters.cmake)
shockgas_clusters_figure(fig_2d_clusters fig_2d MAPS)
