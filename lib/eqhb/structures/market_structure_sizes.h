// A matrix-market structure judged by the size lines of its files alone:
// M, K (and C) square and of one size, and what reading them needs, before
// any entry is read. Without this a stiffness of 2^28 DOFs beside a 2 x 2
// mass was built whole before its size was compared.
#pragma once

#include <string>

namespace eqhb {

// A structure file and the scene key that names it ("structure.stiffness").
struct MarketFile {
  std::string field, path;
};

struct MarketStructureSizes {
  long dofs = 0;
  double stored_entries = 0.0;   // of the files read (C from a damping model not included)
  double reading_bytes = 0.0;    // the largest file's reader temporaries beyond its matrix
};

// Reads the header and size line of each file (damping.path empty when C
// comes from a model) and throws InputError naming the field and the file
// for a bad header, a matrix that is not square or not of the mass matrix's
// size, or one whose reading alone exceeds the memory limit.
MarketStructureSizes checkMarketStructureSizes(const MarketFile& mass, const MarketFile& stiffness,
                                               const MarketFile& damping);

}  // namespace eqhb
