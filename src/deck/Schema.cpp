#include "deck/Schema.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace stentor {

const char* param_type_name(ParamType t) {
  switch (t) {
    case ParamType::Int: return "int";
    case ParamType::Double: return "double";
    case ParamType::Bool: return "bool";
    case ParamType::String: return "string";
    case ParamType::DoubleArray: return "Array(double)";
  }
  return "?";
}

namespace {

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

ParamSpec make(std::string name, ParamType t, std::string doc) {
  ParamSpec p;
  p.name = std::move(name);
  p.type = t;
  p.doc = std::move(doc);
  return p;
}
ParamSpec dbl(std::string name, double d, std::string doc) {
  auto p = make(std::move(name), ParamType::Double, std::move(doc));
  p.num = d;
  return p;
}
ParamSpec integer(std::string name, int d, std::string doc) {
  auto p = make(std::move(name), ParamType::Int, std::move(doc));
  p.num = d;
  return p;
}
ParamSpec boolean(std::string name, bool d, std::string doc) {
  auto p = make(std::move(name), ParamType::Bool, std::move(doc));
  p.num = d ? 1.0 : 0.0;
  return p;
}
ParamSpec str(std::string name, std::string d, std::string doc) {
  auto p = make(std::move(name), ParamType::String, std::move(doc));
  p.str = std::move(d);
  return p;
}
ParamSpec arr(std::string name, std::string doc) {
  return make(std::move(name), ParamType::DoubleArray, std::move(doc));
}

ListSpec list(std::string key, std::string title, std::string doc, std::vector<ParamSpec> params = {}) {
  ListSpec l;
  l.key = std::move(key);
  l.title = std::move(title);
  l.doc = std::move(doc);
  l.params = std::move(params);
  return l;
}

std::vector<ListSpec> build_schema() {
  std::vector<ListSpec> s;

  {
    auto root = list("", "(root)",
                     "The root `<ParameterList>` (any name) holds only sublists; `Mesh`, `Materials` "
                     "and `Bodies` are required.");
    root.sublists = {"Problem", "Mesh", "Materials", "Bodies", "Boundary Conditions", "Initial Conditions",
                     "Time Integration", "Stepping", "Newton", "Linear Solver", "Output", "Contact", "Stages"};
    root.required_sublists = {"Mesh", "Materials", "Bodies"};
    s.push_back(root);
  }

  s.push_back(list("Problem", "Problem", "What is solved.",
                   {str("title", "", "Free text, echoed in the log and the output files."),
                    str("analysis", "static",
                        "`static`: equilibrium at each load step; `dynamic`: momentum balance with inertia "
                        "(see `Time Integration`).")
                        .one_of({"static", "dynamic"}),
                    str("assembly", "atomic",
                        "How threads sum element contributions into shared rows: `atomic` additions, or "
                        "`coloring` (one kernel per colour of cells that share no node, plain additions). "
                        "Results agree to round-off; docs/performance.md compares their speed.")
                        .one_of({"atomic", "coloring"}),
                    str("units", "SI",
                        "The deck's unit system, used only to label plots (nothing is converted: every value is "
                        "taken as given). `SI`: m, kg, s, N, Pa, J; `mm-N-s`: mm, t (tonne), s, N, MPa, mJ; "
                        "`mm-g-ms`: mm, g, ms, N, MPa, mJ; `none`: a dimensionless deck, plots without units. "
                        "In 2D plane strain forces and energies are per unit thickness (N/m, J/m in SI); "
                        "axisymmetric ones are those of the full revolution (N, J).")
                        .one_of({"SI", "mm-N-s", "mm-g-ms", "none"}),
                    str("kinematics", "plane strain",
                        "How a 2D mesh is read. `plane strain`: F_zz = 1, per unit thickness. `axisymmetric`: the "
                        "mesh is a meridian section in the half plane x = r >= 0, y = z (the axis of revolution); "
                        "the hoop stretch is 1 + u_r/r, volumes, areas, masses, loads, reactions and energies are "
                        "those of the full revolution (2 pi r), nodes on the axis (r = 0) get u_r = 0, and the "
                        "output's zz components are the hoop (theta theta) ones (docs/axisymmetric.md). A 3D mesh "
                        "takes the default.")
                        .one_of({"plane strain", "axisymmetric"})}));

  {
    auto l = list(
      "Mesh", "Mesh",
      "The mesh: a gmsh file, or one generated from parameters (`generator`); physical groups name the bodies "
      "and the boundaries.",
      {str("file", "", "Mesh file, relative to the deck's folder (exactly one of `file` and `generator`).")
           .dflt_doc("none")
           .allowed("existing `.msh` or `.geo` file"),
       str("generator", "none",
           "A mesh generated at run time instead of read from `file`: `stent`, the parametric stent of the `Stent` "
           "sublist (docs/stent.md), with the `Balloon` and `Artery` sublists a balloon inside it and an artery around "
           "it; `artery`, the layered artery of the `Artery` sublist (docs/artery.md); `none`: read `file`.")
           .one_of({"none", "stent", "artery"}),
       boolean("write mesh", false,
               "With `generator`: write the generated mesh into the output folder as `<basename>_mesh.msh` (gmsh "
               "ASCII 2.2 with the physical groups, for gmsh or ParaView)."),
       dbl("size", 0.0, "Target element size when meshing a `.geo` (0: the `.geo`'s own).").ge(0.0),
       integer("order", 1, "Element order when meshing a `.geo`: 1 (P1/Q1) or 2 (P2).").one_of({"1", "2"}),
       boolean("recombine", false, "Quadrilaterals (2D) / hexahedra (3D) when meshing a `.geo`."),
       integer("dimension", 0, "Spatial dimension; 0: the highest dimension found in the mesh.")
           .one_of({"0", "2", "3"}),
       dbl("max cells", 5e6,
           "Meshing a `.geo` is refused when the estimated number of cells (bounding box measure / size^dim, "
           "times the cells per size^dim) is above this, a generated stent or artery when its cell count is; raise it to mesh "
           "finer on purpose.")
           .gt(0.0),
       dbl("time limit", 600.0,
           "Seconds gmsh may take to read the mesh file and mesh a `.geo` (it runs in a process of its own); past "
           "them it is stopped and the deck refused (a loop in the `.geo`, a mesh far too fine); raise it for a "
           "slow mesh on purpose.")
           .gt(0.0)});
    l.sublists = {"Stent", "Balloon", "Artery", "Parameters"};
    s.push_back(l);
  }
  {
    auto l = list(
        "Mesh/Parameters", "Mesh->Parameters",
        "Numbers handed to the `.geo` file's `DefineNumber` parameters before gmsh reads it, as gmsh's "
        "`-setnumber` (and its GUI) do: `<Parameter name=\"n\" type=\"double\" value=\"20\"/>` sets the ONELAB "
        "parameter `Parameters/n`, which `n = DefineNumber[40, Name \"Parameters/n\"];` then takes instead of its "
        "default (a name with a `/` is the full ONELAB name). Each entry is a `double` or an `int`, finite. A value "
        "that the `.geo` (with the files it includes) does not read through a `DefineNumber` of that name is refused "
        "(exit 2, naming it and listing the ones it has): a plain `n = 40;` cannot be set. Only with a `.geo` "
        "`file`.");
    l.passthrough = true;  // the entries are the .geo's; deck/Config.cpp checks them
    s.push_back(l);
  }
  s.push_back(list(
      "Mesh/Stent", "Mesh->Stent",
      "The parametric stent of `generator` = `stent` (docs/stent.md): `rings` rings of sinusoidal struts along z, "
      "hex8 cells. Lengths in the deck's length unit. Volume group `stent`; facet groups `inner`, `outer`, "
      "`end_proximal`, `end_distal`, `symmetry_x`, `symmetry_y`, `symmetry_z` (reductions), `ring_<k>`, `links`, "
      "`sides` (the struts' side faces), `inner_and_sides` (the surface a balloon wraps); point `anchor`.",
      {integer("rings", 1, "Number of rings, along z.").ge(1).le(1000),
       integer("crowns", 8, "Crowns per ring: periods of the strut's sinusoidal centreline around the circumference.")
           .ge(2)
           .le(1000),
       dbl("outer diameter", 0.0, "Outer diameter D of the tube [length].").req().gt(0.0),
       dbl("thickness", 0.0, "Radial wall thickness t [length] (below D / 2).").req().gt(0.0),
       dbl("strut width", 0.0,
           "Strut width w [length] in the tube's surface (below half the crown pitch lambda = pi (D - t) / crowns).")
           .req()
           .gt(0.0),
       dbl("ring length", 0.0,
           "Axial extent of one ring [length]: the crowns' peak-to-valley amplitude of the centreline plus the strut "
           "width. The crowns' centreline radius lambda^2 / (4 pi^2 a), a = (ring length - w) / 2, "
           "must exceed w / 2.")
           .req()
           .gt(0.0),
       dbl("gap", 0.0,
           "Axial distance [length] between neighbouring rings' struts at the linked crowns: the links' length. "
           "Required (> 0) with more than one ring.")
           .ge(0.0),
       str("links", "peak-to-peak",
           "How neighbouring rings face each other. `peak-to-peak`: every other ring is mirrored, crowns face crowns "
           "and a link joins two crown tips; `peak-to-valley`: the rings are in phase, a link joins a crown's tip to "
           "the inside of the next ring's crown.")
           .one_of({"peak-to-peak", "peak-to-valley"}),
       integer("links per ring", 0, "Straight axial links between each pair of neighbouring rings (dividing `crowns`).")
           .ge(0)
           .le(1000),
       dbl("link width", 0.0, "Width of a link [length].").ge(0.0).dflt_doc("`strut width`"),
       integer("elements through width", 3, "Hex8 cells across a strut's width.").ge(1).le(100),
       integer("elements through thickness", 3, "Hex8 cells through the wall's thickness.").ge(1).le(100),
       dbl("element length", 0.0, "Target cell length along the struts and links [length].")
           .ge(0.0)
           .dflt_doc("`strut width` / `elements through width`"),
       str("sector", "full",
           "`full`: the whole circumference; `quarter`: 0 <= theta <= 90 deg, cut on the symmetry planes x = 0 "
           "(`symmetry_x`) and y = 0 (`symmetry_y`) through crowns (`crowns` divisible by 4, links symmetric); "
           "`period`: the smallest sector 0 <= theta <= Theta between two symmetry planes through crowns that repeats "
           "the stent, y = 0 (`symmetry_y`) and the oblique plane theta = Theta (`symmetry_sector`, to hold with "
           "Dirichlet `components` = normal): Theta = 180 deg / `crowns` (one strut) without links, a multiple of it "
           "with links (the log names it).")
           .one_of({"full", "quarter", "period"}),
       boolean("half length", false,
               "Only the proximal half, z <= total length / 2, cut on the symmetry plane `symmetry_z` (an even "
               "number of rings with `links` = `peak-to-peak`).")}));

  s.push_back(list(
      "Mesh/Balloon", "Mesh->Balloon",
      "A deformable balloon mounted in the generated stent (`generator` = `stent`; docs/stent.md, \"The deformable "
      "balloon\"): a tube of hex8 cells on the stent's axis, centred on the stent, longer than it, meshed with the "
      "stent's `sector` and `half length`. Volume group `balloon`; facet groups `balloon_inner` (for the inflation "
      "`pressure`), `balloon_outer` (the contact surface the stent's `inner` lies on), `balloon_ends` (the end rings "
      "bonded to the catheter, to hold); its facets on the cut planes join the stent's `symmetry_*` groups.",
      {dbl("outer diameter", 0.0, "Outer diameter as mounted [length], below the stent's inner diameter.")
           .req()
           .gt(0.0),
       dbl("thickness", 0.0, "Wall thickness [length], below the outer radius.").req().gt(0.0),
       dbl("length", 0.0, "Length of the whole balloon [length], longer than the stent (centred on it).").req().gt(0.0),
       integer("elements through thickness", 2, "Hex8 cells through the wall.").ge(1).le(100),
       dbl("element length", 0.0,
           "Target cell size around (at the outer radius) and along [length], at most 50 wall thicknesses.")
           .ge(0.0)
           .dflt_doc("the stent's `strut width`")}));

  s.push_back(list(
      "Mesh/Artery", "Mesh->Artery",
      "The parametric artery of `generator` = `artery` (docs/artery.md): a straight tube along z (0 <= z <= "
      "`length`, axis the z axis) of three concentric layers, structured hex8 cells. Lengths in the deck's length "
      "unit. Volume groups `intima`, `media`, `adventitia` (and `plaque`); facet groups `lumen`, `outer`, `end_proximal`, "
      "`end_distal`, `symmetry_x`, `symmetry_y`, `symmetry_z` (reductions). With `generator` = `stent` the artery "
      "around the generated stent (docs/artery.md, \"Stent and artery in one model\"): centred on the stent, over "
      "its `sector` and `half length` (not given here); facet groups `lumen`, `artery_outer`, `artery_end_proximal`, "
      "`artery_end_distal`, its cut planes in the stent's `symmetry_*` groups.",
      {dbl("inner diameter", 0.0,
           "Diameter of the lumen [length]. Around a stent the lumen's facets, at (inner diameter / 2 - plaque "
           "h_max) cos(180 deg / `elements around`), must lie outside the stent's outer radius.")
           .req()
           .gt(0.0),
       dbl("length", 0.0, "Axial length of the tube [length]; around a stent longer than the stent.").req().gt(0.0),
       dbl("intima thickness", 0.0, "Radial thickness of the intima, the innermost layer [length].").req().gt(0.0),
       dbl("media thickness", 0.0, "Radial thickness of the media, the middle layer [length].").req().gt(0.0),
       dbl("adventitia thickness", 0.0, "Radial thickness of the adventitia, the outer layer [length].").req().gt(0.0),
       integer("elements through intima", 1, "Hex8 cells through the intima's thickness.").ge(1).le(100),
       integer("elements through media", 2, "Hex8 cells through the media's thickness.").ge(1).le(100),
       integer("elements through adventitia", 1, "Hex8 cells through the adventitia's thickness.").ge(1).le(100),
       integer("elements around", 32,
               "Hex8 cells around the whole circumference (divisible by 4 for `sector` = quarter, by 2 for half; "
               "around a stent by the number of the stent's sectors around, 2 `crowns` / the sector's half pitches).")
           .ge(4)
           .le(100000),
       integer("elements along", 8, "Hex8 cells along the whole `length` (even with `half length`).").ge(1).le(100000),
       str("sector", "full",
           "`full`: the whole circumference; `half`: 0 <= theta <= 180 deg (y >= 0), cut on `symmetry_y`; "
           "`quarter`: 0 <= theta <= 90 deg, cut on `symmetry_x` (x = 0) and `symmetry_y` (y = 0). Not with "
           "`generator` = `stent` (the stent's `sector`).")
           .one_of({"full", "half", "quarter"}),
       boolean("half length", false,
               "Only 0 <= z <= `length` / 2, cut on the symmetry plane `symmetry_z`. Not with `generator` = `stent` "
               "(the stent's `half length`)."),
       dbl("plaque stenosis", 0.0,
           "Diameter stenosis S of a plaque (0: none): the lumen's diameter through the plaque's peak, along x, is "
           "(1 - S) times the healthy one. The lumen is narrowed by h = h_max s(z) e(theta), a raised-cosine profile "
           "s along z over `plaque length` and e = 1 (concentric) or (1 + cos theta)/2 (eccentric, on the +x side), "
           "h_max = S Ri or 2 S Ri; the innermost layer's cells inside the healthy lumen form the volume group "
           "`plaque` (docs/artery.md). h_max may not exceed the wall's thickness.")
           .ge(0.0)
           .lt(1.0),
       dbl("plaque length", 0.0, "Axial length of the plaque's profile [length] (required with a plaque).").ge(0.0),
       dbl("plaque centre", -1.0,
           "z of the plaque's peak [length], from the tube's proximal end (around a stent: the stent's middle - "
           "`length` / 2); the middle of `length` by default.")
           .dflt_doc("`length` / 2"),
       str("plaque shape", "concentric",
           "`concentric` or `eccentric` (the plaque on the +x side; not with `sector` = quarter, around a stent "
           "only with the stent's `sector` = full).")
           .one_of({"concentric", "eccentric"}),
       integer("elements through plaque", 2,
               "Hex8 cells added through the innermost layer when there is a plaque (it then spans Ri - h .. Ri + "
               "intima thickness).")
           .ge(1)
           .le(100),
       dbl("centreline radius", 0.0,
           "A gently curved artery: the tube bent in the x-z plane towards +x, its centreline an arc of this radius R "
           "[length] through (0, 0, `length` / 2), tangent to z there (the straight tube's point (x, y, z) goes to "
           "(R - (R - x) cos phi, y, `length` / 2 + (R - x) sin phi), phi = (z - `length` / 2) / R); the end planes stay "
           "planes through the bend's axis. Above the outer radius, `length` / R at most 180 deg, with `sector` full or "
           "half; not around a stent. The layers' Holzapfel-Gasser-Ogden fibres follow it with the material's "
           "`centreline radius` (docs/artery.md, \"A curved artery\"). 0: straight.")
           .ge(0.0)}));

  {
    auto l = list("Materials", "Materials", "Material definitions, referred to by `Bodies-><body>->material`.");
    l.named_sublists = "material";
    s.push_back(l);
  }
  s.push_back(list(
      "Materials/*", "Materials-><material>",
      "A material law (hyperelastic, or with Gauss-point history: plasticity, damage). "
      "Ciarlet-Geymonat: W = C1 (I1 - 3) + C2 (I2 - 3) + D (I3 - 1) "
      "- (C1 + 2 C2 + D) ln I3; small-strain mu = 2 (C1 + C2), lambda = 4 (C2 + D). The elastic constants "
      "are exactly one of three sets: `C1` + `D` (+ `C2`), `E` + `nu`, or `mu` + `lambda`; with E/nu or "
      "mu/lambda, C1 = mu/2 - C2 and D = lambda/4 - C2 with `C2` as given (default 0), both must be > 0 "
      "(docs/deck.md, Materials). neo-Hookean: W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, from E + nu "
      "or mu + lambda. Mooney-Rivlin: W = C1 (I1 - 3) + C2 (I2 - 3) - 2 (C1 + 2 C2) ln J + lam/2 (ln J)^2 "
      "with C1 = mu/2 - C2, lam = lambda - 4 C2 from E + nu or mu + lambda and `C2` (default 0). "
      "Holzapfel-Gasser-Ogden (arteries): the neo-Hookean matrix from E + nu or mu + lambda plus two fibre families, "
      "sum k1/(2 k2) [exp(k2 (I4* - 1)^2) - 1] over I4* = kappa I1 + (1 - 3 kappa) a0.C a0 > 1 (tension only; "
      "unmodified invariants; `kappa` the fibre dispersion, 0 by default; `anisotropy` rho < 1 adds "
      "(1 - rho) (I1 - 3)^2 to each exponent, Holzapfel et al. 2005), a0 at "
      "+-`fibre angle` to the circumferential direction of the cylindrical frame of `axis point` and `axis`. "
      "Plane strain in 2D. "
      "`Ciarlet-Geymonat plasticity` and `neo-Hookean plasticity` add multiplicative von Mises plasticity "
      "F = Fe Ftr with the Mandel stress, yield |M|_H <= sigma_y(alpha) and isotropic hardening (linear, Voce or a table, "
      "`hardening law`) to the "
      "Ciarlet-Geymonat resp. neo-Hookean law (docs/plasticity.md). `neo-Hookean damage`: Miehe's "
      "discontinuous (Mullins-type) damage, W = (1 - d) W0 with W0 the neo-Hookean law, alpha the largest W0 "
      "reached and d = d_inf (1 - exp(-alpha / beta)): unloading and reloading below alpha are elastic with the "
      "softened stiffness. The laws with Gauss-point history (plasticity, damage) run in dynamics with the "
      "gonzalez (energy-dissipative), newmark or hht scheme, not midpoint.",
      {str("model", "Ciarlet-Geymonat", "Constitutive law (docs/deck.md, Materials).")
           .one_of({"Ciarlet-Geymonat", "Ciarlet-Geymonat plasticity", "neo-Hookean", "neo-Hookean plasticity",
                    "neo-Hookean damage", "Mooney-Rivlin", "Holzapfel-Gasser-Ogden"}),
       dbl("C1", 0.0, "First invariant coefficient [stress] (with `D`; not with E/nu or mu/lambda).").gt(0.0)
           .dflt_doc("from E/nu or mu/lambda"),
       dbl("C2", 0.0, "Second invariant coefficient [stress]; with E/nu or mu/lambda it sets the split of mu.").ge(0.0),
       dbl("D", 0.0, "Volumetric coefficient [stress] (with `C1`).").gt(0.0).dflt_doc("from E/nu or mu/lambda"),
       dbl("E", 0.0, "Young's modulus [stress] (with `nu`): mu = E/(2(1+nu)), lambda = E nu/((1+nu)(1-2nu)).")
           .gt(0.0).dflt_doc("none"),
       dbl("nu", 0.0, "Poisson ratio [-] (with `E`).").ge(0.0).lt(0.5).dflt_doc("none"),
       dbl("mu", 0.0, "Small-strain shear modulus (Lame mu) [stress] (with `lambda`).").gt(0.0).dflt_doc("none"),
       dbl("lambda", 0.0, "Small-strain Lame lambda [stress] (with `mu`).").ge(0.0).dflt_doc("none"),
       dbl("k1", 0.0, "Fibre stiffness k1 [stress] of `Holzapfel-Gasser-Ogden` (required there, not allowed with other models).")
           .gt(0.0)
           .dflt_doc("none"),
       dbl("k2", 0.0, "Fibre exponent k2 [-] of `Holzapfel-Gasser-Ogden` (required there).").gt(0.0).dflt_doc("none"),
       dbl("fibre angle", 0.0,
           "Angle beta [deg] of the two fibre families (+beta, -beta) to the circumferential direction, towards the "
           "axis, of `Holzapfel-Gasser-Ogden` (required there): 0 circumferential, 90 axial.")
           .ge(0.0)
           .le(90.0)
           .dflt_doc("none"),
       dbl("kappa", 0.0,
           "Fibre dispersion kappa [-] of `Holzapfel-Gasser-Ogden` (Gasser, Ogden & Holzapfel 2006): the fibre "
           "invariant is I4* = kappa I1 + (1 - 3 kappa) I4; 0 aligned fibres, 1/3 isotropic (docs/artery.md).")
           .ge(0.0)
           .le(1.0 / 3.0),
       dbl("anisotropy", 1.0,
           "Anisotropy rho [-] of `Holzapfel-Gasser-Ogden` in the form of Holzapfel, Sommer, Gasser & Regitnig (2005), "
           "whose human coronary layers use it: each family's exponent is k2 [(1 - rho) (I1 - 3)^2 + rho <I4* - 1>^2]; "
           "1 the fibres alone (the 2000 law), below 1 an isotropic part stiffens every direction (docs/artery.md). "
           "Not with `kappa` > 0.")
           .gt(0.0)
           .le(1.0),
       arr("axis point",
           "A point of the vessel axis of the fibre frame [length] of `Holzapfel-Gasser-Ogden` (one value per dimension; "
           "the radial direction at X is that of X minus its projection on the axis).")
           .len(2, 3)
           .dflt_doc("origin"),
       arr("axis", "Direction of the fibre frame's axis (3 values, normalized) of `Holzapfel-Gasser-Ogden`: (0, 0, 1) "
                   "for a 2D cross-section of a vessel, in the plane for an axial section.")
           .len(3, 3)
           .dflt_doc("(0, 0, 1)"),
       dbl("centreline radius", 0.0,
           "A curved vessel (`Holzapfel-Gasser-Ogden`): the radius [length] of its circular centreline, which passes "
           "through `axis point` tangent to `axis` and curves towards `bend direction`; the fibre frame at X is the "
           "meridian frame of the centreline's point nearest X (axis: the centreline's tangent there). 0: the straight "
           "axis. The curved artery of `Mesh->Artery->centreline radius` R is this frame with `axis point` (0, 0, "
           "`length` / 2), `axis` (0, 0, 1), `bend direction` (1, 0, 0) (docs/artery.md).")
           .ge(0.0),
       arr("bend direction",
           "Unit direction from `axis point` towards the centre of a curved vessel's centreline (normal to `axis`; with "
           "`centreline radius` > 0).")
           .len(3, 3)
           .dflt_doc("(1, 0, 0)"),
       dbl("density", 0.0, "Mass density [density] (dynamics).").ge(0.0),
       dbl("viscosity", 0.0, "Viscosity eta [stress x time] (Curnier); unused in statics.").ge(0.0),
       dbl("yield stress", 0.0,
           "Initial yield stress Y [Pa, the unit of the moduli] of `Ciarlet-Geymonat plasticity` and "
           "`neo-Hookean plasticity` (required there, not allowed with other models nor with `hardening law` = "
           "table, whose first stress is Y): the bound on the Hill (von Mises) norm of the Mandel stress.")
           .gt(0.0)
           .dflt_doc("none"),
       str("hardening law", "linear",
           "Isotropic hardening of `Ciarlet-Geymonat plasticity` and `neo-Hookean plasticity` (docs/plasticity.md, "
           "Hardening laws), the yield stress sigma_y at equivalent plastic strain alpha: `linear`, Y + H alpha; "
           "`Voce`, Y + H alpha + (Y_inf - Y)(1 - exp(-delta alpha)) with `saturation stress` Y_inf and "
           "`saturation rate` delta; `table`, piecewise linear through (`hardening table strains`, "
           "`hardening table stresses`), extrapolated with the slope of the last segment.")
           .one_of({"linear", "Voce", "table"}),
       dbl("hardening", 0.0,
           "Linear isotropic hardening modulus H [Pa, the unit of the moduli] of `Ciarlet-Geymonat plasticity` "
           "and `neo-Hookean plasticity` with `hardening law` = linear or Voce (not table): the yield stress is "
           "Y + H alpha (+ the Voce term; alpha the equivalent plastic strain); 0 is perfect plasticity (linear). "
           "The plastic modulus of the 1D curve sigma_y(alpha), not the elastic-plastic tangent modulus E_t: "
           "H = E E_t / (E - E_t).")
           .ge(0.0),
       dbl("saturation stress", 0.0,
           "Y_inf [Pa, the unit of the moduli] of `hardening law` = Voce (required there, not allowed otherwise), "
           ">= `yield stress`: the Voce term of the yield stress saturates at Y_inf - Y.")
           .gt(0.0)
           .dflt_doc("none"),
       dbl("saturation rate", 0.0,
           "delta [-] of `hardening law` = Voce (required there, not allowed otherwise): the Voce term is "
           "(Y_inf - Y)(1 - exp(-delta alpha)), 63% saturated at alpha = 1/delta.")
           .gt(0.0)
           .dflt_doc("none"),
       arr("hardening table strains",
           "Equivalent plastic strains eps_i [-] of `hardening law` = table (required there, not allowed "
           "otherwise): 2 to 32 values, the first 0, strictly increasing.")
           .len(2, 32)
           .ge(0.0)
           .dflt_doc("none"),
       arr("hardening table stresses",
           "Yield stresses sigma_i [Pa, the unit of the moduli] at `hardening table strains` (same count; required "
           "with `hardening law` = table): the first is the initial yield stress Y, non-decreasing (no softening).")
           .len(2, 32)
           .gt(0.0)
           .dflt_doc("none"),
       str("plastic dynamic step", "incremental potential",
           "Stress of the momentum equation in the `gonzalez` dynamic step of `Ciarlet-Geymonat plasticity` and "
           "`neo-Hookean plasticity` (docs/plasticity.md, Dynamics): `incremental potential`, the discrete gradient "
           "of the step's incremental potential (the plastic flow of the step inside the stress, off the yield "
           "surface by O(dt^2); plastic dissipation Y dalpha); `mean value`, the return-map stress at a mean-value "
           "point of the same potential (on the yield surface, but its Newton iteration can stall where the "
           "hardening is weak: the point is then not unique); `lagged`, the discrete gradient of the elastic energy "
           "at the plastic state of the step's start (the flow enters the stress one step late, overshooting the "
           "yield surface by O(dt); cheapest). All keep the energy balance exact.")
           .one_of({"incremental potential", "mean value", "lagged"}),
       dbl("saturation damage", 0.0,
           "d_inf [-] of `neo-Hookean damage` (required there, not allowed with other models): the damage d = "
           "d_inf (1 - exp(-alpha / beta)) tends to it as the largest virgin energy alpha grows; 0 is the "
           "neo-Hookean law.")
           .ge(0.0)
           .lt(1.0)
           .dflt_doc("none"),
       dbl("damage energy scale", 0.0,
           "beta [Pa = J/m^3, the unit of the moduli] of `neo-Hookean damage` (required there): the virgin "
           "strain-energy density at which d reaches 63% of d_inf.")
           .gt(0.0)
           .dflt_doc("none")}));

  {
    auto l = list("Bodies", "Bodies", "The bodies to simulate (at least one): each is a mesh physical group made of one material.");
    l.named_sublists = "body";
    s.push_back(l);
  }
  s.push_back(list("Bodies/*", "Bodies-><body>", "One body; the sublist name is the body's name.",
                   {str("physical group", "", "Mesh physical group of the body's elements.").allowed("physical group name")
                        .dflt_doc("the sublist name"),
                    str("material", "", "Name of a sublist of `Materials`.").req().allowed("a defined material"),
                    str("element technology", "full",
                        "The element formulation of the body's cells. `full`: the standard displacement element, "
                        "fully integrated. `f-bar`: hex8 with the F-bar formulation of de Souza Neto et al. (1996): "
                        "every Gauss point's law sees F (J0/J)^(1/3), J0 = det F at the cell centre, which removes "
                        "the volumetric locking of nearly incompressible elasticity and isochoric plastic flow "
                        "(docs/elements.md). Static analysis only, hex8 cells only (a body with other cells, or a "
                        "dynamic analysis, is refused).")
                        .one_of({"full", "f-bar"}),
                    arr("initial velocity",
                        "This body's uniform initial velocity [velocity] (dynamic analysis), one value per dimension; it "
                        "replaces `Initial Conditions` velocity and angular velocity on the body's nodes (a node "
                        "shared with another body takes the value of the body listed last).")
                        .len(2, 3)
                        .dflt_doc("`Initial Conditions`"),
                    arr("initial angular velocity",
                        "This body's initial rigid rotation rate [1 / time] about `rotation center` (dynamic analysis): 1 "
                        "value (about z) in 2D, 3 in 3D. With it the body's v0 = `initial velocity` (0 if not given) + "
                        "angular velocity x (X - rotation center), replacing `Initial Conditions` velocity and angular "
                        "velocity on its nodes.")
                        .len(1, 3)
                        .dflt_doc("`Initial Conditions`"),
                    arr("rotation center", "Centre of the body's initial rotation [length], one value per dimension.")
                        .len(2, 3)
                        .dflt_doc("required with `initial angular velocity`"),
                    arr("initial displacement",
                        "This body's uniform initial displacement [length] (dynamic analysis), one value per dimension; it "
                        "replaces `Initial Conditions` displacement on the body's nodes (shared nodes: the body listed "
                        "last). Prescribed dofs keep their prescribed values.")
                        .len(2, 3)
                        .dflt_doc("`Initial Conditions`")}));

  {
    auto l = list("Boundary Conditions", "Boundary Conditions",
                  "Loads and prescribed displacements. Parameters common to all types are in the "
                  "next table, type-specific ones in the tables after it. A load's name (its sublist name) heads CSV "
                  "columns and plot labels: letters, digits, spaces and `_ . + -` only, at most 100 characters.");
    l.named_sublists = "load";
    s.push_back(l);
  }
  s.push_back(list(
      "Boundary Conditions/*", "Boundary Conditions-><load>",
      "Parameters of every load. The load is multiplied by the ramp factor at time t.",
      {str("type", "", "Kind of load (case-insensitive).")
           .req()
           .one_of({"Dirichlet", "traction", "pressure", "body force", "fluid cavity"}),
       str("ramp", "linear", "Time function: `linear` (t / end time), `constant` (1), `table`.")
           .one_of({"linear", "constant", "table"}),
       arr("ramp times", "`table` ramp: strictly increasing times [time].")
           .len(2, 0)
           .dflt_doc("required for `table`"),
       arr("ramp factors", "`table` ramp: factors at `ramp times` (same length); constant beyond the ends.")
           .len(2, 0)
           .dflt_doc("required for `table`")}));
  s.push_back(list("Boundary Conditions/*/Dirichlet", "Boundary Conditions-><load> (type = Dirichlet)",
                   "Prescribed displacement of a boundary.",
                   {str("boundary", "", "Mesh physical group of the constrained boundary.").req().allowed("physical group name"),
                    str("components", "all",
                        "Constrained displacement components. `normal`: the displacement along the boundary's unit "
                        "outward normal only (a roller or symmetry plane at any angle: the boundary must be planar); "
                        "the node slides freely in the plane, and the reaction is normal to it.")
                        .allowed("`x`, `y`, `z` separated by spaces or commas, or `all`, or `normal`"),
                    arr("values", "Displacement [length] of each listed component, in the order listed.")
                        .len(1, 3)
                        .dflt_doc("zeros")
                        .allowed("one per listed component (for `all`: one per dimension; for `normal`: one)")}));
  s.push_back(list("Boundary Conditions/*/traction", "Boundary Conditions-><load> (type = traction)",
                   "Dead load: a fixed traction per unit reference area.",
                   {str("boundary", "", "Mesh physical group of the loaded boundary.").req().allowed("physical group name"),
                    arr("traction", "Traction vector [stress], one value per dimension.").req().len(2, 3)}));
  s.push_back(list("Boundary Conditions/*/pressure", "Boundary Conditions-><load> (type = pressure)",
                   "Follower pressure: acts against the current outward normal.",
                   {str("boundary", "", "Mesh physical group of the loaded boundary.").req().allowed("physical group name"),
                    dbl("pressure", 0.0, "Pressure [stress]; positive pushes into the body.").req()}));
  s.push_back(list(
      "Boundary Conditions/*/fluid cavity", "Boundary Conditions-><load> (type = fluid cavity)",
      "Volume control of a balloon (3D, static stages): the cavity enclosed by `boundary`, by planes normal to the "
      "axis (its ends) and by planes through the axis (symmetry cuts) holds a fluid of bulk modulus K. Its volume "
      "at zero pressure is V0 (1 + ramp(t) (`volume ratio` - 1)), V0 the cavity's volume in the mesh; the "
      "pressure on `boundary` is p = K ln(V_fluid / V), V the cavity's current volume, so a large K prescribes "
      "V (a plateau of the pressure is passed). The ratio is the same for a symmetry sector as for the whole "
      "balloon. The history has `pressure_<load>` and `volume_ratio_<load>` (V / V0).",
      {str("boundary", "", "Mesh physical group of the cavity's wall, facets oriented out of the body (e.g. "
                           "`balloon_inner`).").req().allowed("physical group name"),
       dbl("volume ratio", 1.0, "V_fluid / V0 at ramp factor 1.").req().gt(0.0),
       dbl("bulk modulus", 0.0, "The fluid's bulk modulus K [stress] (water: 2.2 GPa).").req().gt(0.0),
       arr("axis point", "A point of the cavity's axis [length].").req().len(3, 3),
       arr("axis", "The cavity's axis direction.").req().len(3, 3)}));
  s.push_back(list("Boundary Conditions/*/body force", "Boundary Conditions-><load> (type = body force)",
                   "Force per unit reference volume.",
                   {str("body", "", "A body: its `Bodies` sublist name or its physical group.").dflt_doc("all bodies"),
                    arr("force", "Force density [force / volume], one value per dimension.").req().len(2, 3)}));

  s.push_back(list(
      "Initial Conditions", "Initial Conditions",
      "Initial state of every body (dynamic analysis): u0 = displacement (uniform), "
      "v0 = velocity + angular velocity x (X - center). Constrained dofs keep their prescribed values.",
      {arr("displacement", "Uniform initial displacement [length], one value per dimension.").len(2, 3).dflt_doc("zeros"),
       arr("velocity", "Uniform initial velocity [velocity], one value per dimension.").len(2, 3).dflt_doc("zeros"),
       arr("angular velocity",
           "Rigid rotation rate [1 / time]: 1 value (about z) in 2D, 3 values in 3D.")
           .len(1, 3)
           .dflt_doc("zeros"),
       arr("center", "Centre of the rigid rotation [length].").len(2, 3).dflt_doc("origin")}));

  s.push_back(list(
      "Time Integration", "Time Integration",
      "Time scheme of a dynamic analysis. The midpoint family (gonzalez, midpoint) updates "
      "v_{n+1} = 2 (u_{n+1} - u_n) / dt - v_n; `gonzalez` evaluates the elastic stress with "
      "Gonzalez's discrete gradient so the discrete energy balance holds exactly; `midpoint` "
      "evaluates it at F_{n+1/2} (not energy-consistent); `newmark` is average acceleration; "
      "`hht` is Hilber-Hughes-Taylor with numerical dissipation set by `hht alpha`.",
      {str("scheme", "gonzalez", "Time integration scheme.").one_of({"gonzalez", "midpoint", "newmark", "hht"}),
       dbl("hht alpha", -0.1, "HHT parameter alpha (0: Newmark average acceleration).").ge(-1.0 / 3.0).le(0.0)}));

  s.push_back(list(
      "Stepping", "Stepping",
      "Load/time stepping. A step whose Newton solve fails is retried from the last converged state with half "
      "the step; after each accepted step the step grows by `growth` again, up to the deck's step (end time / "
      "steps). The run stops with exit status 3 when a step would need more than `max cutbacks` halvings in a "
      "row, a step smaller than `min dt`, or more than `max steps` steps. Rejected steps write no output.",
      {dbl("end time", 1.0, "Final time [time].").gt(0.0),
       integer("steps", 1, "Number of steps (initial step = end time / steps, which must be at least 1e-300 and "
               "1e-12 x end time).").ge(1),
       integer("max cutbacks", 6, "Halvings of a failed step in a row before giving up.").ge(0),
       dbl("growth", 1.5, "Factor by which the step grows after each accepted step until it is the deck's step again.")
           .ge(1.0)
           .le(4.0),
       dbl("stabilization", 0.0,
           "Static steps: viscous stabilisation of bodies that float until contact holds them (a stent's struts, a "
           "balloon). Each free dof gets the force xi K_ii (u - u_n), K_ii its tangent diagonal at the step's start "
           "and xi this factor (dimensionless; 1e-6 to 1e-3 typical): a dashpot over the step that makes the tangent "
           "regular without changing the equilibrium of a body at rest. The energy it absorbs (xi K_ii du^2 per step, "
           ">= 0) is the history CSV's `stabilization_energy` and is printed at the end; the run warns when it exceeds "
           "1 % of the final strain energy. 0: off. A stage may set its own (`Stages-><s>->stabilization`). docs/contact.md, "
           "\"Bodies held only by contact\".")
           .ge(0.0)
           .le(1.0),
       integer("target iterations", 0,
               "Newton iterations a step should take: 0 (off) or at least 4 (a solve to the tolerances takes 2 to 3). "
               "With T > 0 the step follows the solve (Crisfield's rule): after a step that took n iterations the next is "
               "sqrt(T / n) times it, between 1/2 and `growth`, never above the deck's step, and not larger after a step "
               "in which a contact node entered or left contact; "
               "each change is printed with its reason, and the history CSV's `dt` column holds the steps taken. "
               "Contact scenes: docs/contact.md, \"Step size\".")
           .ge(0)
           .le(1000),
       dbl("contact approach", 0.0,
           "Steps that land on the contact: a step is shortened so that no slave node of a part of its slave surface "
           "that touches nothing yet (a strut, a stent ring before the balloon reaches it) is predicted to end it "
           "deeper than this many times its size (tributary length, or the square root of its tributary area in 3D) "
           "inside its obstacle or master surface; nodes and master nodes move as the predictor extrapolates (statics) "
           "or with their velocity (dynamics), rigid obstacles as prescribed. Printed with its reason; the step then "
           "grows back by `growth`. Node-to-segment and rigid pairs. 0: off. docs/contact.md, \"Steps that land on "
           "the contact\".")
           .ge(0.0)
           .le(1.0),
       dbl("min dt", 0.0, "Smallest step [time]: a cut-back below it ends the run (exit 3). 0: 1e-6 x (end time / steps).")
           .ge(0.0)
           .dflt_doc("`0` (1e-6 x end time / steps)"),
       integer("max steps", 0, "Cap on the number of steps tried, accepted and rejected (exit 3 when reached). "
               "0: 100 x steps + 1000.")
           .ge(0)
           .dflt_doc("`0` (100 x steps + 1000)"),
       str("predictor", "auto",
           "Newton's first iterate of a step. `auto`: statics extrapolate the last increment, and lift the "
           "prescribed increment where there is none to extrapolate (the first step); dynamics start at u_n. "
           "`none`: u_n. `extrapolate` (statics): the last increment extrapolated (u_n on the first step). "
           "`velocity` (dynamics): u_n + dt v_n (midpoint family), u_n + dt v_n + dt^2/2 a_n "
           "(newmark, hht). `lifting`: every step, one linear solve with the tangent at u_n whose prescribed rows "
           "carry the increment of the prescribed values, so it is spread into the interior instead of "
           "squeezing the boundary layer of cells (counted as a Newton iteration). Prescribed dofs take their "
           "values in every case, and a guess that inverts elements is retried from u_n. Measured in "
           "docs/robustness.md and docs/performance.md.")
           .one_of({"auto", "none", "extrapolate", "velocity", "lifting"})}));

  s.push_back(list(
      "Newton", "Newton",
      "Newton-Raphson on the residual r (Dirichlet rows excluded; global 2-norms), with a backtracking line "
      "search. With ref = max(norm(r_0), force scale), r_0 the residual of the step's first guess, a step has "
      "converged when the contact active sets did not change in the last evaluation and either norm(r) <= "
      "max(`relative residual tolerance` x ref, `absolute residual tolerance`) with, after the first iteration, "
      "the last correction norm(alpha du) at most 1e-2 of norm(u - u_0), u_0 the first guess (the residual test), or the "
      "last increment satisfies norm(alpha du) <= `increment tolerance` x norm(u) while norm(r) <= "
      "sqrt(`relative residual tolerance`) x ref (the increment test), or Newton's correction norm(du) is below "
      "the round-off of the coordinates, 8 eps (norm(X) + norm(u)) (machine precision reached; off, like the increment "
      "test, with `increment tolerance` = 0). The force scale "
      "and the exact rule: docs/deck.md, \"Newton convergence\".",
      {integer("max iterations", 25,
               "Iterations per step before a cutback, counted from the last revision of contact nodes held after "
               "cycling (a revision starts Newton over from a converged point; at most 4 per step).")
           .ge(1),
       dbl("relative residual tolerance", 1e-10,
           "rtol: the residual test norm(r) <= max(rtol x ref, atol), ref = max(norm(r_0), force scale); "
           "sqrt(rtol) x ref bounds the residual of the increment test. The dynamic default keeps the energy "
           "identity to about 1e-12 of the energy per run (docs/deck.md, \"Newton convergence\").")
           .ge(0.0)
           .lt(1.0)
           .dflt_doc("1e-12 in a dynamic analysis or stage, 1e-10 in a static one"),
       dbl("absolute residual tolerance", 0.0,
           "atol [force]: a floor of the residual test's target (an absolute residual, not relative); 0: "
           "none, the test is relative to ref only (a fixed floor in force units stopped Newton after one "
           "iteration on small loads).")
           .ge(0.0),
       dbl("increment tolerance", 1e-10,
           "The increment test, an alternative to the residual test: norm(alpha du) <= tol x norm(u) and "
           "norm(r) <= sqrt(rtol) x ref (a residual limited by round-off).")
           .ge(0.0),
       boolean("line search", true, "Backtracking line search on norm(r)."),
       integer("line search max halvings", 6, "Maximum halvings of the Newton step.").ge(0),
       integer("line search watchdog", 2,
               "Non-monotone watchdog steps. Contact active sets: after this many consecutive iterations whose "
               "full step changed a contact active set and was damped by the line search, the next full step that "
               "changes the set is taken without the decrease test, so the semi-smooth Newton moves to the new set "
               "instead of creeping along halved steps. Creeping: after this many consecutive iterations damped to "
               "alpha <= 1/8, the next full step is taken without the decrease test; unless the residual falls "
               "below the point before it within 3 iterations, Newton returns to that point and takes the damped "
               "step (Chamberlain's watchdog, once per solve). 0: never (strictly monotone). Measured on "
               "inputs/s4_stent_artery.xml: 15 cut-backs and 1346 Newton iterations without the creeping rule, 9 "
               "and 1095 with it (docs/contact.md).")
           .ge(0),
       str("forcing", "eisenstat-walker",
           "Tolerance of each iteration's linear solve (GMRES; a direct solve is exact). `eisenstat-walker`: "
           "inexact Newton, eta_k = 0.9 (norm(r_k) / norm(r_k-1))^2 (Eisenstat and Walker's choice 2 with their "
           "safeguard), at most `forcing max`, at least `Linear Solver->tolerance`, first `forcing max` in a static "
           "step and 0.9 q^2 in a dynamic one (q: the last dynamic step's first residual ratio); the iteration expected to be "
           "the last (eta_k norm(r_k) below half the convergence target) is solved to `Linear Solver->tolerance`, "
           "so the final iterate is as accurate as with `fixed` and results on different rank counts agree to "
           "round-off (1e-12 in S1's contact force). `fixed`: every solve to `Linear Solver->tolerance`. The "
           "convergence test is the same either way, and so are the solution and the energy identity. 3D cube, "
           "4 load steps: 1.3x (P1 22k DOF) and 1.26x (P2 24k DOF) faster than `fixed` (docs/performance.md).")
           .one_of({"fixed", "eisenstat-walker"}),
       dbl("forcing max", 0.1, "Upper bound of the Eisenstat-Walker forcing term, and its first value.")
           .gt(0.0)
           .lt(1.0),
       dbl("max increment", 0.0,
           "Step-length control [length]: an update du whose largest component exceeds this value is "
           "scaled down to it before the line search (0: no limit). For bodies that only their inertia "
           "restrains in some direction (a frictionless stent strut squeezed between balloon and wall). S4 "
           "(inputs/s4_stent_artery.xml) uses 0.01, a tenth of the strut radius: mu = 0 went from 46 to 35 "
           "cut-backs, 2973 to 2469 Newton iterations (docs/scenes/README.md).")
           .ge(0.0)}));

  {
    auto l = list(
        "Linear Solver", "Linear Solver",
        "Linear solves inside Newton. The optional sublists `Belos`, `Ifpack2`, `MueLu` and "
        "`Amesos2` are passed to Trilinos unchanged and override the values here.",
        {str("method", "gmres", "Krylov (Belos GMRES) or sparse direct (`direct solver`).").one_of({"gmres", "direct"}),
         str("direct solver", "auto",
             "The sparse direct solver of `method` = direct. `klu2`: Amesos2's KLU2, a serial LU: on several ranks "
             "every Newton iteration gathers the matrix on one rank. `mumps`: MUMPS (the MPI build of Debian's "
             "libmumps-dev), which factors the matrix across the ranks with a fill-reducing ordering: faster on "
             "several ranks and in 3D, but on several ranks its results vary at round-off from run to run (a restart "
             "there is not bit for bit; docs/solvers.md). `auto`: klu2.")
             .one_of({"auto", "klu2", "mumps"}),
         str("preconditioner", "auto",
             "Additive Schwarz (Ifpack2), algebraic multigrid (MueLu) or none. `auto`: `muelu` where "
             "this build's Trilinos has MueLu (Debian's does), else `schwarz`; the log's `solver` line says which.")
             .one_of({"auto", "schwarz", "muelu", "none"}),
         dbl("tolerance", 1e-10, "Relative residual of each linear solve.").gt(0.0).lt(1.0),
         integer("max iterations", 1000, "Krylov iterations per solve.").ge(1),
         integer("restart", 200, "GMRES Krylov subspace size.").ge(1),
         integer("overlap", 1, "Schwarz overlap (layers).").ge(0),
         str("subdomain solver", "RILUK", "Schwarz subdomain solver (KLU2 via Amesos2).")
             .one_of({"RILUK", "ILUT", "KLU2"}),
         integer("fill level", 1, "RILUK level of fill.").ge(0),
         integer("preconditioner reuse", 20,
                 "GMRES: how many later Newton iterations (and steps) may keep a preconditioner built for an "
                 "earlier tangent of the same matrix instead of rebuilding it (0: rebuilt every iteration). It is "
                 "rebuilt earlier when the last solve did not converge, when the iterations it has lost since "
                 "its build add up to `preconditioner rebuild cost`, or when the contact active set changed "
                 "(`preconditioner rebuild on contact change`). A stale preconditioner changes only the "
                 "Krylov iterations, not the Newton iterate's accuracy. Measured in docs/performance.md.")
             .ge(0),
         dbl("preconditioner rebuild cost", 25.0,
             "GMRES: what building the preconditioner is worth, in GMRES iterations. A kept preconditioner is "
             "rebuilt once the iterations it has cost beyond a fresh one's rate (iterations per digit of "
             "residual reduction of the first solve after its build, +25 %) add up to this. The decision uses "
             "only iteration counts, so runs stay reproducible. A MueLu build measured about 25 iterations' worth "
             "on 2 and 16 ranks (docs/performance.md, \"Rebuilding a stale preconditioner\"); raise it where "
             "builds are dearer. 0: rebuilt after the first solve that loses any.")
             .ge(0.0),
         boolean("preconditioner rebuild on contact change", true,
                 "GMRES: build the preconditioner afresh for a tangent whose contact active set (or a node's "
                 "stick/slip state) changed at its point. On 16 ranks at 200k DOF this took the S2 torus's Newton "
                 "solves from 51 s to 46 s; on 30k DOF and 1-2 ranks, where builds are dear next to the short "
                 "solves, it costs 3-5 % (docs/performance.md, \"Rebuilding a stale preconditioner\").")});
    l.sublists = {"Belos", "Ifpack2", "MueLu", "Amesos2"};
    s.push_back(l);
  }
  for (const char* pkg : {"Belos", "Ifpack2", "MueLu", "Amesos2"}) {
    auto l = list(std::string("Linear Solver/") + pkg, std::string("Linear Solver->") + pkg,
                  std::string("Passed to ") + pkg + " unchanged (see the Trilinos documentation); not validated here.");
    l.passthrough = true;
    s.push_back(l);
  }

  {
    auto l = list("Output", "Output", "Result files.",
                  {str("directory", "results/{deck}", "Output folder (relative to the working directory); `{deck}` stands for "
                      "the deck's file name without `.xml`, so each deck has its own folder by default; `--output` "
                      "overrides. A run writes only into a new or empty folder or a Stentor results folder, never "
                      "into the deck's own folder."),
                   str("basename", "stentor", "File name stem.").allowed("letters, digits, spaces, `_ . + -`; at most 100 characters"),
                   integer("every", 1, "Write fields every N converged steps (and at t = 0, at `times`, at the end of every stage and of the run).").ge(1),
                   boolean("fields", true, "HDF5/XDMF field output on/off."),
                   str("field list", "default",
                       "The fields written (docs/deck.md, \"Outputs\"): names separated by commas or spaces; "
                       "`default` stands for the standard set (displacement, cauchy_stress, von_mises, J, mpi_rank, "
                       "the plastic and contact fields the deck has), `all` for every field the deck has. An unknown "
                       "name, or one the deck cannot have (velocity in statics, contact fields without `Contact`), "
                       "is an error.")
                       .allowed("field names, `default`, `all`"),
                   arr("times", "Times [time] at which fields are also written, strictly increasing, in (0, end time]. "
                                "A step that would pass one is shortened to end on it (the steps after it keep "
                                "their size). Fields are always written at t = 0, at the end of the run and of "
                                "every stage."),
                   dbl("interval", 0.0,
                       "Time [time] between field outputs: fields are also written at every multiple of it up to the end "
                       "time, merged with `times` (a step that would pass one is shortened to end on it), so the "
                       "output times are regular whatever the cut-backs. 0: off (`every` counts accepted steps). At "
                       "most 100,000 outputs.")
                       .ge(0.0),
                   integer("checkpoint every", 0,
                           "Write a checkpoint (the whole state, `<basename>_checkpoint.h5` in the output folder, "
                           "the one before kept as `<basename>_checkpoint.prev.h5`) every N accepted steps and at the "
                           "end of the run (and of each stage); `stentor --restart FILE DECK` continues from it. "
                           "0: no checkpoints.")
                       .ge(0)});
    l.sublists = {"Probes", "Stent Metrics"};
    s.push_back(l);
  }
  s.push_back(list(
      "Output/Stent Metrics", "Output->Stent Metrics",
      "Stent metrics after every accepted step in <basename>_metrics.csv and at the end of each stage in "
      "<basename>_stages.csv and the log. Radii are distances of the current node positions from the vessel axis "
      "(the line through `axis point` along `axis`). A stent in an artery (S4, docs/scenes/README.md) names its "
      "groups: lumen and stent radii, artery stresses, and with the axis in the model (2D axial section, 3D) "
      "dogboning and foreshortening from the stent's axial extent; with the axis normal to a 2D model (a "
      "cross-section) the lumen area is that of the `lumen` curve (star-shaped about the axis point). A generated "
      "stent (`Mesh->generator` = stent) names nothing: its groups and axis come from the generator and the "
      "metrics are those of docs/stent.md (\"Stent metrics\"): outer diameters per ring at the crowns and "
      "overall, at the links, length, foreshortening, radial and longitudinal recoil, dogboning, the largest "
      "equivalent plastic strain and where, mass and metal-to-artery ratio, and a diameter plot; with an artery "
      "generated around it (`Mesh->Artery`) also the lumen's mean and minimum diameter over the stented segment "
      "and their gains, and per layer the largest principal stress (maximum and 99th percentile; docs/artery.md, "
      "\"Artery metrics\"). In an "
      "axisymmetric run (`Problem->kinematics`) the vessel axis is the axis of revolution: `axis point` (0, z), `axis` "
      "(0, 1, 0); radii are the nodes' r = x and the circumferential stress is the hoop stress sigma_thth "
      "(docs/axisymmetric.md).",
      {arr("axis point", "A point of the vessel axis [length] (one value per dimension).")
           .len(2, 3)
           .dflt_doc("required; not with `Mesh->generator` = stent (the z axis through the origin)"),
       arr("axis", "Direction of the vessel axis (3 values, normalized): in the plane for an axial section, (0, 0, 1) "
                   "for a 2D cross-section.")
           .len(3, 3)
           .dflt_doc("required; not with `Mesh->generator` = stent"),
       str("stent", "", "Boundary group of the stent surface that faces the lumen: its radius is the stent radius.")
           .allowed("physical group name")
           .dflt_doc("required; not with `Mesh->generator` = stent"),
       str("lumen", "", "Boundary group of the artery's inner surface (axial section: measured over the stent's "
                        "reference axial span).")
           .allowed("physical group name")
           .dflt_doc("required; not with `Mesh->generator` = stent"),
       str("artery", "", "Volume group (body) of the artery wall: maximum von Mises and circumferential Cauchy "
                         "stress (circumferential direction: axis x radial at the cell's reference centroid).")
           .allowed("physical group name")
           .dflt_doc("required; not with `Mesh->generator` = stent"),
       dbl("end fraction", 0.2, "Dogboning of a stent in an artery: the stent's ends are its nodes within this "
                                "fraction of its reference length from either end, its middle those within this "
                                "fraction around the centre (a generated stent compares its end and centre rings).")
           .gt(0.0)
           .le(0.5),
       dbl("malapposition threshold", 0.0,
           "A generated stent in a generated artery: an `outer` node of the stent farther than this from the lumen "
           "surface [length] counts as malapposed (the `malapposed_area` metric: the share of the stent's outer "
           "surface off the wall), and so does a strut whose outer surface's mean distance exceeds it (`malapposed_struts`; "
           "docs/artery.md, \"Artery metrics\"). 0: a tenth of the strut thickness.")
           .ge(0.0)}));
  {
    auto l = list("Output/Probes", "Output->Probes", "Points whose displacement history is recorded. Probe names "
                  "head CSV columns: letters, digits, spaces and `_ . + -` only, at most 100 characters.");
    l.named_sublists = "probe";
    s.push_back(l);
  }
  s.push_back(list("Output/Probes/*", "Output->Probes-><probe>", "One probe; the sublist name names its output column. The nearest node is probed.",
                   {arr("point", "Reference coordinates [length] (2 or 3 values).").req().len(2, 3)}));
  {
    auto l = list("Contact", "Contact",
                  "Frictional contact of slave nodes against rigid analytic obstacles or the boundary of another "
                  "deformable body (docs/contact.md), solved by the primal-dual active set "
                  "(semi-smooth Newton) method inside the Newton loop. Without this sublist no contact work is done. "
                  "Pair names head CSV columns: letters, digits, spaces and `_ . + -` only, at most 100 characters.");
    l.named_sublists = "contact pair";
    s.push_back(l);
  }
  s.push_back(list(
      "Contact/*", "Contact-><pair>",
      "One contact pair: the nodes of a boundary group against either an analytic rigid obstacle (`obstacle`), which "
      "may translate (translation x ramp) and change radius (radius change x radius ramp), or the boundary facets of "
      "another deformable body (`master`, node-to-segment: the reaction acts on the master facet's nodes). Signed gap "
      "d >= 0 on the body's side.",
      {str("slave", "", "Mesh physical group (boundary) whose nodes may touch the obstacle.").req().allowed("physical group name"),
       str("obstacle", "",
           "Rigid obstacle shape: `circle` (2D), `cylinder` (3D, infinite), `sphere` (3D), `plane`, `capsule` (2D or "
           "3D: the points within `radius` of the segment from `point` to `point` + `length` `axis`; a balloon: in 2D "
           "its axial section, a stadium).")
           .allowed("`plane`, `circle`, `cylinder`, `sphere`, `capsule`")
           .dflt_doc("one of `obstacle`, `master` is required"),
       str("master", "",
           "Boundary physical group (line2/line3 facets in 2D, tri3/tri6/quad4 in 3D) of another deformable body: the "
           "master surface. The slave nodes' contact forces act on it, distributed by the facet shape functions.")
           .allowed("physical group name")
           .dflt_doc("one of `obstacle`, `master` is required"),
       arr("point", "A point of the plane; the centre of a circle/sphere; a point of the cylinder axis; the capsule segment's start [length].")
           .len(2, 3)
           .dflt_doc("required for `obstacle`"),
       arr("normal", "Plane: normal pointing to the body's side (normalized).").len(2, 3).dflt_doc("required for `plane`"),
       arr("axis", "Cylinder, capsule: axis direction (normalized); 3 values for a cylinder, one per dimension for a capsule.")
           .len(2, 3)
           .dflt_doc("required for `cylinder`, `capsule`"),
       dbl("length", 0.0, "Capsule: length of the axis segment [length] (0: a circle or sphere).").ge(0.0).dflt_doc("required for `capsule`"),
       dbl("radius", 1.0, "Radius of circle, cylinder, sphere, capsule [length].").gt(0.0).dflt_doc("required for curved obstacles"),
       str("side", "outside",
           "`outside`: the body is outside the obstacle (a rod, a balloon); `inside`: the body is inside (a tube wall).")
           .one_of({"outside", "inside"}),
       arr("translation", "Rigid translation of the obstacle [length], one value per dimension, times the translation ramp.")
           .len(2, 3)
           .dflt_doc("zeros"),
       str("translation ramp", "linear", "Time function of the translation: `linear`, `constant`, `table`.")
           .one_of({"linear", "constant", "table"}),
       arr("translation ramp times", "`table`: strictly increasing times [time].").len(2, 0).dflt_doc("required for `table`"),
       arr("translation ramp factors", "`table`: factors at the times.").len(2, 0).dflt_doc("required for `table`"),
       dbl("radius change", 0.0, "Radius increment [length] (balloon inflation) times the radius ramp; curved obstacles only."),
       str("radius ramp", "linear", "Time function of the radius change.").one_of({"linear", "constant", "table"}),
       arr("radius ramp times", "`table`: strictly increasing times [time].").len(2, 0).dflt_doc("required for `table`"),
       arr("radius ramp factors", "`table`: factors at the times.").len(2, 0).dflt_doc("required for `table`"),
       dbl("friction", 0.0, "Coulomb friction coefficient mu (0: frictionless).").ge(0.0),
       str("formulation", "auto",
           "`persistence`: persistency condition on the discrete normal velocity with leapfrog gap prediction "
           "(energy-conserving); `gap`: standard KKT conditions on the end-of-step gap; `auto`: persistence in "
           "dynamics, gap in statics.")
           .one_of({"auto", "persistence", "gap"}),
       str("discretization", "node-to-segment",
           "Pairs with `master`: `node-to-segment` (each slave node against the closest point of one master facet; "
           "the reaction goes to that facet's nodes by its shape functions; any facet type) or `mortar` (dual mortar, "
           "segment-based integration: each slave node's weighted gap against the master facets that overlap its "
           "facets, the normal averaged over the slave facets at the node, the reaction spread over the master nodes "
           "by the mortar weights; transmits a uniform pressure exactly across non-matching meshes, the patch test; "
           "line2, line3, tri3, quad4 facets on both sides; in axisymmetry the integrals and the dual basis carry 2 pi r). See docs/contact.md, Mortar.")
           .one_of({"node-to-segment", "mortar"}),
       dbl("c normal", 0.0,
           "Active-set parameter c_nu (> 0) of the normal complementarity function, per unit area of the slave "
           "surface: [stress x time / length] with persistence (it multiplies the normal velocity), [stress / length] with gap; each node uses "
           "c_nu times its tributary area, so the multipliers compare as pressures and one value means the same on "
           "every mesh (the talk's 1e4). 0: automatic (the node's tangent diagonal, times dt for persistence).")
           .ge(0.0),
       dbl("c tangent", 0.0,
           "Active-set parameter c_tau [stress x time / length] of the friction complementarity function, per unit area like `c normal`; "
           "0: automatic (the node's tangent diagonal times dt).")
           .ge(0.0),
       str("set update", "linearised",
           "Which multiplier decides the active and stick/slip sets at a Newton iterate. `linearised`: the "
           "multiplier of the last linear solve (primal-dual active set: zero on the nodes that were inactive in it, "
           "the force the linearised problem needed on the active ones), so the decision follows the sign of the gap "
           "for an inactive node and of the force for an active one, whatever c_nu and c_tau; `residual`: the node's "
           "bulk residual at the iterate (the condensed multiplier), whose nonlinear remainder can decide the set "
           "when c is small. See docs/contact.md, Active sets.")
           .one_of({"linearised", "residual"})}));
  {
    auto l = list("Stages", "Stages",
                  "A procedure of consecutive stages (Abaqus steps), run in the order listed; state (displacement, "
                  "velocity, contact history) carries over. Each stage has a duration and steps, the loads and contact "
                  "pairs active in it, its analysis (static or dynamic) and time scheme, and optional ramps in "
                  "stage-local time. Without `Stages` the run is one "
                  "interval [0, `Stepping->end time`]; with it, `Stepping->end time` and `steps` are not used (the other "
                  "`Stepping` parameters apply to every stage, `min dt` 0 meaning 1e-6 x each stage's step). "
                  "Stage names appear in the log and head no file: letters, digits, spaces and `_ . + -` only, at most 100 characters.");
    l.named_sublists = "stage";
    s.push_back(l);
  }
  {
    auto l = list(
        "Stages/*", "Stages-><stage>",
        "One stage, the interval (start, end] with start the previous stage's end (0 for the first). An active "
        "load's factor is its ramp (the stage's `Ramps` entry, else the load's own) at stage-local time t - start, "
        "`linear` meaning (t - start) / duration. A Dirichlet set that is not active holds its value from the end "
        "of the stage before (0 before its first stage); a traction, pressure or body force that is not active is "
        "0. An inactive contact pair enforces nothing (its nodes are free) and its obstacle holds its position and "
        "radius; an active obstacle moves by its ramps in stage-local time. Each stage has its own `analysis` and "
        "`scheme` (Abaqus: a static step after a dynamic one): a static stage starts at rest (the velocity of the "
        "stage before is set to 0 and its kinetic energy is not carried), a dynamic stage after a static one starts "
        "at rest from the static state; contact pairs with `formulation` = auto use persistence in dynamic stages "
        "and the gap condition in static ones. The energy CSV holds the dynamic stages, with a row at the start of "
        "each dynamic stage that follows a static one.",
        {dbl("duration", 1.0, "Length of the stage [time].").gt(0.0).dflt_doc("one of `duration`, `end time` is required"),
         dbl("end time", 1.0, "End of the stage on the procedure's clock [time].").gt(0.0)
             .dflt_doc("one of `duration`, `end time` is required"),
         integer("steps", 1, "Number of steps of the stage (initial step = duration / steps).").ge(1),
         dbl("step", 1.0, "Step size instead of `steps` [time]: steps = duration / step, rounded up.").gt(0.0)
             .dflt_doc("duration / `steps`"),
         str("analysis", "static", "`static` or `dynamic` (see `Problem->analysis`).")
             .one_of({"static", "dynamic"})
             .dflt_doc("`Problem->analysis`"),
         str("scheme", "gonzalez", "Time scheme of a dynamic stage (see `Time Integration`); not allowed in a static stage.")
             .one_of({"gonzalez", "midpoint", "newmark", "hht"})
             .dflt_doc("`Time Integration->scheme`"),
         dbl("stabilization", 0.0, "Viscous stabilisation factor of the stage's static steps (see `Stepping->stabilization`); not allowed in a dynamic stage.")
             .ge(0.0)
             .le(1.0)
             .dflt_doc("`Stepping->stabilization`"),
         str("loads", "all", "The `Boundary Conditions` active in the stage: `all`, `none`, or names separated by commas.")
             .allowed("`all`, `none`, or load names separated by commas"),
         str("contact", "all", "The `Contact` pairs active in the stage: `all`, `none`, or names separated by commas.")
             .allowed("`all`, `none`, or pair names separated by commas")});
    l.sublists = {"Ramps"};
    s.push_back(l);
  }
  {
    auto l = list("Stages/*/Ramps", "Stages-><stage>->Ramps",
                  "Ramps of this stage, in stage-local time, that replace a load's `ramp` or an obstacle's "
                  "`translation ramp` / `radius ramp` (the rigid balloon: insert by translation, inflate and deflate "
                  "by radius change). One sublist per active load or contact pair, named like it.");
    l.named_sublists = "load or contact pair";
    s.push_back(l);
  }
  s.push_back(list(
      "Stages/*/Ramps/*", "Stages-><stage>->Ramps-><load or pair>",
      "A load takes `ramp` (+ times, factors); a rigid obstacle `translation ramp` and `radius ramp` (+ times, "
      "factors). Factors multiply the load's values, the obstacle's `translation` and `radius change`; times are "
      "stage-local [time].",
      {str("ramp", "linear", "Load: `linear` (stage-local t / duration), `constant`, `table`.").one_of({"linear", "constant", "table"}),
       arr("ramp times", "`table`: strictly increasing stage-local times [time].").len(2, 0).dflt_doc("required for `table`"),
       arr("ramp factors", "`table`: factors at the times.").len(2, 0).dflt_doc("required for `table`"),
       str("translation ramp", "linear", "Obstacle translation: `linear`, `constant`, `table`.").one_of({"linear", "constant", "table"}),
       arr("translation ramp times", "`table`: strictly increasing stage-local times [time].").len(2, 0).dflt_doc("required for `table`"),
       arr("translation ramp factors", "`table`: factors at the times.").len(2, 0).dflt_doc("required for `table`"),
       str("radius ramp", "linear", "Obstacle radius change: `linear`, `constant`, `table`.").one_of({"linear", "constant", "table"}),
       arr("radius ramp times", "`table`: strictly increasing stage-local times [time].").len(2, 0).dflt_doc("required for `table`"),
       arr("radius ramp factors", "`table`: factors at the times.").len(2, 0).dflt_doc("required for `table`")}));
  return s;
}

}  // namespace

bool ParamSpec::in_range(double v) const {
  if (std::isnan(v)) return false;
  if (has_min && (min_open ? !(v > min) : !(v >= min))) return false;
  if (has_max && (max_open ? !(v < max) : !(v <= max))) return false;
  return true;
}

std::string ParamSpec::range_text() const {
  if (has_min && has_max)
    return std::string("in ") + (min_open ? "(" : "[") + fmt(min) + ", " + fmt(max) + (max_open ? ")" : "]");
  if (has_min) return std::string(min_open ? "> " : ">= ") + fmt(min);
  if (has_max) return std::string(max_open ? "< " : "<= ") + fmt(max);
  return "";
}

std::string ParamSpec::default_text() const {
  if (required) return "**required**";
  if (!default_doc.empty()) return default_doc;
  switch (type) {
    case ParamType::Int:
    case ParamType::Double: return "`" + fmt(num) + "`";
    case ParamType::Bool: return num != 0.0 ? "`true`" : "`false`";
    case ParamType::String: return str.empty() ? "`\"\"`" : "`" + str + "`";
    case ParamType::DoubleArray: return "none";
  }
  return "";
}

std::string ParamSpec::allowed_text() const {
  std::vector<std::string> parts;
  if (!choices.empty()) {
    std::string c;
    for (size_t i = 0; i < choices.size(); ++i) c += (i ? ", `" : "`") + choices[i] + "`";
    parts.push_back(c);
  }
  if (has_range()) parts.push_back(type == ParamType::DoubleArray ? "each " + range_text() : range_text());
  if (type == ParamType::DoubleArray && (min_len > 0 || max_len > 0)) {
    if (min_len == max_len)
      parts.push_back(std::to_string(min_len) + " values");
    else if (max_len == 0)
      parts.push_back(">= " + std::to_string(min_len) + " values");
    else
      parts.push_back(std::to_string(min_len) + (max_len == min_len + 1 ? " or " : " to ") + std::to_string(max_len) +
                      " values");
  }
  if (type == ParamType::Bool) parts.push_back("`true`, `false`");
  if (!allowed_doc.empty()) parts.push_back(allowed_doc);
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
  return out.empty() ? "any" : out;
}

const ParamSpec* ListSpec::find(const std::string& n) const {
  for (const auto& p : params)
    if (p.name == n) return &p;
  return nullptr;
}

const std::vector<ListSpec>& deck_schema() {
  static const std::vector<ListSpec> schema = build_schema();
  return schema;
}

const ListSpec& deck_list_spec(const std::string& key) {
  for (const auto& l : deck_schema())
    if (l.key == key) return l;
  throw std::logic_error("stentor: no deck schema entry '" + key + "'");
}

void print_deck_schema_markdown(std::ostream& os) {
  os << "<!-- BEGIN parameter tables: generated by stentor::deck_schema_markdown() "
        "(src/deck/Schema.cpp); do not edit by hand -->\n";
  for (const auto& l : deck_schema()) {
    if (l.key.empty()) continue;  // the root is described in the hand-written part
    os << "\n### `" << l.title << "`\n\n" << l.doc << "\n";
    if (!l.named_sublists.empty())
      os << "\nContains one sublist per " << l.named_sublists << " (any name).\n";
    if (!l.sublists.empty()) {
      os << "\nSublists:";
      for (size_t i = 0; i < l.sublists.size(); ++i) os << (i ? ", `" : " `") << l.sublists[i] << "`";
      os << ".\n";
    }
    if (!l.params.empty()) {
      os << "\n| Parameter | Type | Default | Allowed | Description |\n"
            "|---|---|---|---|---|\n";
      auto cell = [](std::string t) {
        for (std::size_t i = 0; (i = t.find('|', i)) != std::string::npos; i += 2) t.insert(i, "\\");
        return t;
      };
      for (const auto& p : l.params)
        os << "| `" << cell(p.name) << "` | " << param_type_name(p.type) << " | " << cell(p.default_text()) << " | "
           << cell(p.allowed_text()) << " | " << cell(p.doc) << " |\n";
    }
  }
  os << "\n<!-- END parameter tables -->\n";
}

std::string deck_schema_markdown() {
  std::ostringstream os;
  print_deck_schema_markdown(os);
  return os.str();
}

int edit_distance_ci(const std::string& a0, const std::string& b0) {
  const std::string a = lower(a0), b = lower(b0);
  std::vector<int> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string nearest_name(const std::string& name, const std::vector<std::string>& candidates) {
  std::string best;
  int best_d = 1 << 30;
  for (const auto& c : candidates) {
    const int d = edit_distance_ci(name, c);
    if (d < best_d) best_d = d, best = c;
  }
  if (best.empty()) return "";
  const int limit = std::max<int>(2, static_cast<int>(name.size()) / 3);
  if (best_d <= limit) return best;
  // A name that contains (or is contained in) a candidate is a likely abbreviation.
  const std::string ln = lower(name);
  if (ln.size() >= 3)
    for (const auto& c : candidates) {
      const std::string lc = lower(c);
      if (lc.size() < 3) continue;  // 'e' or 'nu' is in too many words to be an abbreviation
      if (lc.find(ln) != std::string::npos || ln.find(lc) != std::string::npos) return c;
    }
  return "";
}

}  // namespace stentor
