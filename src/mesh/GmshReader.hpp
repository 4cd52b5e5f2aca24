// Reading a mesh through the gmsh C++ API (.msh 4.1/2.2 ascii or binary, or a
// .geo meshed on the fly). Call on one rank only (gmsh is a process-wide
// singleton; not thread-safe), then broadcast_mesh() the result or send each rank its
// part (mesh/MeshPart.hpp distribute_mesh).
#pragma once
#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// Reads cfg.file into a Mesh.
//  * .msh: read as is (cfg.size/order/recombine are ignored).
//  * .geo (anything else gmsh can open as a model is treated the same way):
//    meshed with
//      - cfg.size > 0: a uniform target size: Mesh.MeshSizeMax = size and
//        Mesh.MeshSizeFromPoints = 0, so the .geo's own point sizes ("h") are
//        ignored (transfinite curves/surfaces in the .geo still win);
//        cfg.size == 0: the .geo's own sizes;
//      - Mesh.ElementOrder = cfg.order, Mesh.SecondOrderIncomplete = 1
//        (P2 = tri6 / tet10);
//      - cfg.recombine: 2D: Mesh.RecombineAll = 1 (Blossom: quad4, normally
//        all quads; any leftover triangles are kept in their own block); 3D: Mesh.SubdivisionAlgorithm = 2 (every tet split into 4
//        hexes, so the hexes are about half the size). Recombine needs
//        order 1 (quad8/hex20 bodies are not supported).
//  * Dimension: cfg.dimension, or (0) the highest dimension of any physical group.
//  * Physical groups of that dimension -> Mesh::volumes (one CellBlock per
//    (group, cell type), groups in gmsh's (dim, tag) order, types in gmsh type
//    order); lower-dimension groups -> Mesh::boundaries (facets, edges, points
//    as node sets). Names from the .geo/.msh, or "tag<N>" when unnamed.
//  * Nodes: every node used by a kept cell, numbered 0..N-1 in increasing gmsh
//    node tag order (deterministic).
//  * Volume cell ids: 0..Nc-1 over Mesh::volumes in block order; boundary cell
//    ids: 0..Nf-1 over Mesh::boundaries in block order (a separate numbering).
//  * A .geo is first screened (mesh/GeoScreen.hpp: no command that runs a program,
//    writes a file, ends the process or meshes by itself), and meshing is refused when
//    the cell estimate (bounding box measure / size^dim; size = cfg.size, or the mean
//    curve element length of the .geo's own sizes) is above cfg.max_cells; gmsh running
//    out of memory is an InputError too.
// Throws InputError (message starting with the file path) when the file is
// missing or unreadable, gmsh fails to parse/mesh it (gmsh's message is
// quoted), there is no physical group of the mesh dimension, a cell type is not
// supported, two volume groups share an entity, or a 2D mesh is not in the
// z = 0 plane. Orientation is NOT fixed here: a clockwise 2D surface gives
// det J < 0 everywhere, which check_mesh() reports.
// verbose: let gmsh print its progress to the terminal.
//  * With enable_gmsh_process() (stentor's main does it), gmsh runs in a child process
//    (this executable with --gmsh-helper) limited to cfg.time_limit seconds and the
//    machine's memory: a crash, an exit, a hang or running out of memory in gmsh is an
//    InputError naming the file ("gmsh crashed ...", "... within 'Mesh->time limit'"),
//    and nothing gmsh writes (preferences) lands in the user's HOME. The child confines
//    itself with Landlock before gmsh reads anything (mesh/Confine.hpp: it writes only
//    in its temporary folder, reads only the screened files and system libraries); the
//    log says when the kernel cannot. Without it (unit tests) gmsh runs in this process.
//  * Files larger than the input size limits (deck/InputLimits.hpp) are refused unread.
//  * cfg.generator not empty (a mesh generated from the deck's parameters, e.g. `stent`):
//    the generator set by set_mesh_generator() makes it, in this process; no file is read.
Mesh read_mesh(const MeshConfig& cfg, bool verbose = false);

// The function read_mesh() calls for cfg.generator (src/geometry's generate_mesh; the
// mesh layer does not see the generators). Without one such a cfg is a logic error.
using MeshGenerator = Mesh (*)(const MeshConfig& cfg);
void set_mesh_generator(MeshGenerator g);

// Makes read_mesh() run gmsh in a child process started from `exe`, which must answer
// `exe --gmsh-helper ...` by calling gmsh_helper_main() (before MPI or Kokkos start).
void enable_gmsh_process(const std::string& exe);

// The child's side: reads and meshes as read_mesh() does in-process, writes the Mesh
// (or the error) into the folder argv[2]; exit 0, 2 (input error) or 1.
int gmsh_helper_main(int argc, char** argv);

}  // namespace stentor
