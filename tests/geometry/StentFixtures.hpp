// The stent the generator tests start from: the S6 ring as cut, in mm (OD 3, strut
// 0.1 x 0.1, 8 crowns, ring length 1, gaps of 0.3 between rings), one ring.
#pragma once
#include "deck/StentConfig.hpp"

namespace stentor::test {

inline StentConfig s6_ring_as_cut() {
  StentConfig s;
  s.rings = 1;
  s.crowns = 8;
  s.outer_diameter = 3.0;
  s.thickness = 0.1;
  s.strut_width = 0.1;
  s.ring_length = 1.0;
  s.gap = 0.3;
  return s;
}

// Two rings of it linked at every crown (8 links per ring): 2.3 mm long; the balloon's and
// the artery's generator tests mount their bodies in it.
inline StentConfig s6_two_rings_linked() {
  StentConfig s = s6_ring_as_cut();
  s.rings = 2;
  s.links_per_ring = 8;
  return s;
}

}  // namespace stentor::test
