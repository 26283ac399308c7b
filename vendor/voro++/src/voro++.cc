// Voro++, a 3D cell-based Voronoi library
//
// Author   : Chris H. Rycroft (Harvard University / LBL)
// Email    : chr@alum.mit.edu
// Date     : August 30th 2011

/** \file voro++.cc
 * \brief A file that loads all of the function implementation files. */

#include "cell.cc"
#include "common.cc"
#include "v_base.cc"
#include "container.cc"
#include "unitcell.cc"
#include "container_prd.cc"
#include "pre_container.cc"
#include "v_compute.cc"
#include "c_loops.cc"
#include "wall.cc"
