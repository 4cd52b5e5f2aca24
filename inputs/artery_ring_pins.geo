// The artery ring of artery_ring.geo plus four point groups where the outer
// circle crosses the axes, to remove the rigid-body modes of the free ring
// (fix x at "north"/"south", y at "east"/"west"). The points are arc end points,
// hence mesh nodes. Physical groups: surface "artery"; curves "lumen", "outer";
// points "east" (ro, 0), "north" (0, ro), "west" (-ro, 0), "south" (0, -ro).
// (Kept apart from artery_ring.geo, whose groups the mesh tests pin down.)
Include "artery_ring.geo";

Physical Point("east") = {2};
Physical Point("north") = {3};
Physical Point("west") = {4};
Physical Point("south") = {5};
