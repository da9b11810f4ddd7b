// Faces no sensor can see: a wall face whose front lies inside another wall's body. Plans
// model a layered wall as separate walls side by side (a party wall of CMU with a furring
// wall against it: the Duplex's 2O2Fr$t4X7Zf8NOew3FKRi and 0iEHWY1$XA8eQeeULq4jE6), and the
// two faces where they touch are inside the solid. As landmarks they are walls that are not
// there: a pose a wall-thickness off (the furring's 0.15 m, a party wall's 0.49 m) finds the
// real face's plane "explained" by the buried one behind it.
#pragma once

#include <bimloc/bim/building.hpp>

#include <vector>

namespace bimloc::bim {

// Per face of the storey (index 2 * wall + face): true when at least kBuriedShare of the
// face's length has another wall's body right in front of it (2 cm along its normal) over
// heights the face has.
std::vector<bool> buriedFaces(const bim::Storey& storey);

constexpr double kBuriedShare = 0.8;

}  // namespace bimloc::bim
