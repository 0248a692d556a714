// SOFA's MeshTetraStuffing (master 2a278d891f): how a lattice tetrahedron crossing the surface is
// kept, cut into one to three tetrahedra at the crossing points, or dropped (addTetra,
// addFinalTetra, flipDiag, needFlip, getSplitPoint).
#include "mesh_tetra_stuffing_lattice.h"

#include <utility>

namespace fastcorot::stuffing_detail {

void StuffingBuilder::add(int p1, int p2, int p3, int p4) {
  if (volume6(points_[at(p1)], points_[at(p2)], points_[at(p3)], points_[at(p4)]) < 0) std::swap(p3, p4);
  const int in[4] = {inside_[at(p1)], inside_[at(p2)], inside_[at(p3)], inside_[at(p4)]};
  const int p[4] = {p1, p2, p3, p4};
  int neg[4], pos[4], zero[4];
  int nneg = 0, npos = 0, nzero = 0;
  for (int i = 0; i < 4; ++i) {
    if (in[i] < 0) {
      neg[nneg++] = p[i];
    } else if (in[i] > 0) {
      pos[npos++] = p[i];
    } else {
      zero[nzero++] = p[i];
    }
  }
  if (npos == 0 && nneg > 0) return;
  if (nneg == 0 || !split_) {
    add_final(p1, p2, p3, p4, false);
  } else if (npos == 1) {
    // One tetrahedron: the outside points moved to the crossings toward the inside one.
    const int q[4] = {in[0] < 0 ? cut(p1, pos[0]) : p1, in[1] < 0 ? cut(p2, pos[0]) : p2,
                      in[2] < 0 ? cut(p3, pos[0]) : p3, in[3] < 0 ? cut(p4, pos[0]) : p4};
    add_final(q[0], q[1], q[2], q[3], false);
  } else if (npos == 2 && nneg == 1) {
    const int p0 = zero[0];
    const int cut1 = cut(neg[0], pos[0]), cut2 = cut(neg[0], pos[1]);
    const bool flip_d = flip_diagonal(pos[0], pos[1], cut2, neg[0]);
    const bool flip_t = need_flip(p0, pos[0], pos[1], neg[0], p1, p2, p3, p4);
    if (!flip_d) {
      add_final(p0, pos[0], pos[1], cut2, flip_t);
      add_final(p0, pos[0], cut2, cut1, flip_t);
    } else {
      add_final(p0, pos[0], pos[1], cut1, flip_t);
      add_final(p0, pos[1], cut2, cut1, flip_t);
    }
  } else if (npos == 2 && nneg == 2) {
    const int cut1 = cut(neg[0], pos[0]), cut2 = cut(neg[0], pos[1]);
    const int cut3 = cut(neg[1], pos[0]), cut4 = cut(neg[1], pos[1]);
    const bool flip_a = flip_diagonal(pos[0], pos[1], cut2, neg[0]);
    const bool flip_b = flip_diagonal(pos[0], pos[1], cut4, neg[1]);
    const bool flip_t = need_flip(pos[0], pos[1], neg[0], neg[1], p1, p2, p3, p4);
    if (!flip_a && flip_b) {
      add_final(pos[0], pos[1], cut2, cut3, flip_t);
      add_final(pos[0], cut2, cut1, cut3, flip_t);
      add_final(pos[1], cut2, cut3, cut4, flip_t);
    } else if (flip_a && !flip_b) {
      add_final(pos[0], pos[1], cut1, cut4, flip_t);
      add_final(pos[1], cut1, cut4, cut2, flip_t);
      add_final(pos[0], cut1, cut3, cut4, flip_t);
    }
    // Both diagonals alike: SOFA reports an invalid split and adds nothing.
  } else {  // three inside, one outside
    const int cut1 = cut(neg[0], pos[0]), cut2 = cut(neg[0], pos[1]), cut3 = cut(neg[0], pos[2]);
    const bool flip1 = flip_diagonal(pos[0], pos[1], cut2, neg[0]);
    const bool flip2 = flip_diagonal(pos[1], pos[2], cut3, neg[0]);
    bool flip3 = flip_diagonal(pos[2], pos[0], cut1, neg[0]);
    if (flip1 == flip2 && flip2 == flip3) flip3 = !flip1;  // SOFA: "invalid split", then this
    const int pp0 = (flip1 && !flip2) ? pos[1] : (flip2 && !flip3) ? pos[2] : pos[0];
    const int pc0 = (!flip1 && flip2) ? cut2 : (!flip2 && flip3) ? cut3 : cut1;
    const bool flip_t = need_flip(neg[0], pos[0], pos[1], pos[2], p1, p2, p3, p4);
    add_final(pp0, cut1, cut3, cut2, flip_t);
    add_final(pc0, pos[0], pos[1], pos[2], flip_t);
    if (flip1 == flip2) {
      add_final(pos[1], cut2, pp0, pc0,
                need_flip(pos[1], neg[0], pp0, pp0 == pos[0] ? pos[2] : pos[0], p1, p2, p3, p4));
    } else if (flip2 == flip3) {
      add_final(pos[2], cut3, pp0, pc0,
                need_flip(pos[2], neg[0], pp0, pp0 == pos[0] ? pos[1] : pos[0], p1, p2, p3, p4));
    } else {
      add_final(pos[0], cut1, pp0, pc0,
                need_flip(pos[0], neg[0], pp0, pp0 == pos[1] ? pos[2] : pos[1], p1, p2, p3, p4));
    }
  }
}

void StuffingBuilder::add_final(int p1, int p2, int p3, int p4, bool flip) {
  if (flip) std::swap(p3, p4);
  if (volume6(points_[at(p1)], points_[at(p2)], points_[at(p3)], points_[at(p4)]) < 0) std::swap(p3, p4);
  tetrahedra.push_back({p1, p2, p3, p4});
}

int StuffingBuilder::cut(int from, int to) const {
  if (auto it = cuts_.find({from, to}); it != cuts_.end()) return it->second;
  if (auto it = cuts_.find({to, from}); it != cuts_.end()) return it->second;
  return from;
}

bool StuffingBuilder::flip_diagonal(int a, int b, int c, int e) const {
  const int second = lattice_.second;
  if (e < second) {
    if (a < second) return true;
    if (b < second) return false;
  } else {
    if (a >= second) return true;
    if (b >= second) return false;
  }
  int greater = 0;
  for (int i = 0; i < 3; ++i) {
    if (points_[at(a)][i] > points_[at(c)][i]) ++greater;
  }
  return (greater & 1) != (a < second ? 1 : 0);
}

bool StuffingBuilder::need_flip(int p1, int p2, int p3, int p4, int q1, int q2, int q3, int q4) {
  bool flip = false;
  const auto rotate4 = [](int& a, int& b, int& c, int& d) {
    const int first = a;
    a = b;
    b = c;
    c = d;
    d = first;
  };
  while (p1 > p2 || p1 > p3 || p1 > p4) {
    rotate4(p1, p2, p3, p4);
    flip = !flip;
  }
  while (q1 > q2 || q1 > q3 || q1 > q4) {
    rotate4(q1, q2, q3, q4);
    flip = !flip;
  }
  const auto rotate3 = [](int& b, int& c, int& d) {
    const int first = b;
    b = c;
    c = d;
    d = first;
  };
  while (p2 > p3 || p2 > p4) rotate3(p2, p3, p4);
  while (q2 > q3 || q2 > q4) rotate3(q2, q3, q4);
  if (p3 == q4) flip = !flip;
  return flip;
}

}  // namespace fastcorot::stuffing_detail
