// A plain VQF driver, written the way a user would: reads a BROAD CSV (header
// t,gyr_x..z,acc_x..z,mag_x..z,...) with std::ifstream, std::getline and std::strtod, runs
// VQF's 9D filter (github.com/dlaidig/vqf, C++ version) sample by sample and writes
// t,qw,qx,qy,qz with fprintf. The sample period is the first two rows' time difference.
// tools/scripts/bench-replay.sh times it beside headingd-replay doing the same job. Not part of
// the build: VQF is not a Debian package and its code is not copied here.
//
// Usage: vqf-csv-driver IN.csv OUT.csv
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

#include "vqf.hpp"

namespace {

// The first 10 numbers of a row: t, gyr, acc, mag.
bool parseRow(const std::string& line, double values[10]) {
  const char* p = line.c_str();
  for (int i = 0; i < 10; ++i) {
    char* end = nullptr;
    values[i] = std::strtod(p, &end);
    if (end == p) return false;
    p = *end == ',' ? end + 1 : end;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s IN.csv OUT.csv\n", argv[0]);
    return 2;
  }
  std::ifstream in(argv[1]);
  std::string line;
  if (!in || !std::getline(in, line)) {
    std::fprintf(stderr, "%s: cannot read\n", argv[1]);
    return 1;
  }
  std::FILE* out = std::fopen(argv[2], "w");
  if (out == nullptr) {
    std::fprintf(stderr, "%s: cannot open\n", argv[2]);
    return 1;
  }
  std::fputs("t,qw,qx,qy,qz\n", out);
  std::unique_ptr<VQF> vqf;
  double first[10];
  bool have_first = false;
  double row[10];
  auto update = [&](const double r[10]) {
    vqf->update(r + 1, r + 4, r + 7);
    vqf_real_t q[4];
    vqf->getQuat9D(q);
    std::fprintf(out, "%.9g,%.9f,%.9f,%.9f,%.9f\n", r[0], q[0], q[1], q[2], q[3]);
  };
  while (std::getline(in, line)) {
    if (!parseRow(line, row)) continue;
    if (!have_first) {  // wait for the second row: it gives the sample period
      std::copy(row, row + 10, first);
      have_first = true;
      continue;
    }
    if (!vqf) {
      vqf = std::make_unique<VQF>(row[0] - first[0]);
      update(first);
    }
    update(row);
  }
  if (std::fclose(out) != 0) return 1;
  return 0;
}
