// Rigid obstacles for ParaView and meshio: at every field output the surfaces of the rigid
// obstacles (their position and radius at that time) in <dir>/<basename>_obstacles.xdmf +
// .h5, written by io/XdmfWriter.hpp (a temporal collection of one Uniform grid per output
// time, as the field file: ParaView's XDMF readers and meshio's TimeSeriesReader read it;
// open it next to <basename>.xdmf and both play together). 2D: line segments (XDMF
// "Polyline", NodesPerElement 2) around circles and capsules (stadiums) and along planes, in
// z = 0; 3D: quadrilaterals (sphere, capsule, and cylinder and plane cut to the size of the
// mesh). One block per obstacle in deck order, named after its contact pair: the cell field
// cell_block (0, 1, ...) tells them apart, the Information "cell_block" names them. The
// grid's Geometry is the step's own /step_<k>/coordinates (the obstacles move and inflate);
// node field "displacement" = the positions minus those of the first output (meshio reads the
// first step's points only). Rank 0 only.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "io/XdmfWriter.hpp"

namespace stentor {

// An obstacle's shape at one time (the same fields as contact::Obstacle, kept free of
// the contact headers): kind 0 plane, 1 circle / sphere, 2 cylinder, 3 capsule.
struct ObstacleShape {
  int kind = 0;
  std::array<double, 3> point{}, normal{}, axis{};
  double radius = 0.0, length = 0.0;
};

// Sampled surface: points, and cells as point index lists (lines in 2D, quads in 3D).
struct ObstacleSurface {
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<int>> cells;
};

// `extent`: the mesh's bounding-box diagonal, `centre` its centre (planes and cylinders
// are drawn that large around it).
ObstacleSurface sample_obstacle(const ObstacleShape& o, int dim, double extent, const std::array<double, 3>& centre);

class ObstacleWriter {
 public:
  // `names`: the obstacles' contact pairs, in the order write() gets their shapes.
  ObstacleWriter(std::string dir, std::string basename, int dim, double extent, std::array<double, 3> centre,
                 std::vector<std::string> names);
  ~ObstacleWriter();
  // One output time: the shapes (as many as names, the same kinds every time). Throws
  // WriteError naming the file.
  void write(double t, const std::vector<ObstacleShape>& shapes);

 private:
  std::string dir_, basename_;
  int dim_;
  double extent_;
  std::array<double, 3> centre_;
  std::vector<std::string> names_;
  std::unique_ptr<XdmfWriter> xdmf_;  // created by the first write(), whose points are the reference
  std::vector<double> x0_;
};

}  // namespace stentor
