// Rigid obstacles for ParaView: at every field output the surfaces of the rigid
// obstacles (their position and radius at that time) as VTK XML polydata,
// <dir>/<basename>_obstacles_<k>.vtp, and a time series <dir>/<basename>_obstacles.pvd
// that ParaView opens next to the .xdmf. 2D: closed polylines (circle, capsule =
// stadium) or a segment (plane) in z = 0; 3D: quadrilateral surfaces (sphere, capsule,
// cylinder and plane cut to the size of the mesh). Cell data "obstacle" numbers the
// obstacles in deck order. Rank 0 only.
#pragma once
#include <array>
#include <string>
#include <vector>

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

class ObstacleVtkWriter {
 public:
  ObstacleVtkWriter(std::string dir, std::string basename, int dim, double extent, std::array<double, 3> centre);
  // One output time: writes the .vtp of all shapes and rewrites the .pvd. Throws
  // WriteError naming the file.
  void write(double t, const std::vector<ObstacleShape>& shapes);

 private:
  std::string dir_, basename_;
  int dim_;
  double extent_;
  std::array<double, 3> centre_;
  std::vector<std::pair<double, std::string>> steps_;
};

}  // namespace stentor
