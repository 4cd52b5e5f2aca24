// Reading a Stentor HDF5 result file in tests (read-only): the output steps' times (the
// "time" attribute of /step_<k>), the dataset names of a step, a dataset's values.
#pragma once
#include <hdf5.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace stentor::testing {

struct H5Results {
  hid_t f;
  explicit H5Results(const std::filesystem::path& p) : f(H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~H5Results() {
    if (f >= 0) H5Fclose(f);
  }
  H5Results(const H5Results&) = delete;
  H5Results& operator=(const H5Results&) = delete;
  bool has(const std::string& path) const { return H5Lexists(f, path.c_str(), H5P_DEFAULT) > 0; }
  std::vector<double> times() const {
    std::vector<double> t;
    for (int k = 0; has("/step_" + std::to_string(k)); ++k) {
      const hid_t a = H5Aopen_by_name(f, ("/step_" + std::to_string(k)).c_str(), "time", H5P_DEFAULT, H5P_DEFAULT);
      double v = -1.0;
      H5Aread(a, H5T_NATIVE_DOUBLE, &v);
      H5Aclose(a);
      t.push_back(v);
    }
    return t;
  }
  std::set<std::string> names(int step) const {
    std::set<std::string> n;
    const hid_t g = H5Gopen2(f, ("/step_" + std::to_string(step)).c_str(), H5P_DEFAULT);
    H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, nullptr,
               [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
                 static_cast<std::set<std::string>*>(out)->insert(name);
                 return 0;
               },
               &n);
    H5Gclose(g);
    return n;
  }
  std::vector<double> read(const std::string& path) const {
    std::vector<double> v;
    const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
    if (d < 0) return v;
    const hid_t sp = H5Dget_space(d);
    v.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(sp)));
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Sclose(sp);
    H5Dclose(d);
    return v;
  }
};

}  // namespace stentor::testing
