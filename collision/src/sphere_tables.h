#pragma once
// The sphere prefilter's data as the SIMD kernels see it: plain float tables behind raw pointers,
// owned by SpherePrefilter (sphere_prefilter.h). This header includes nothing from the standard
// library but <cstdint>'s type names on purpose: it is also compiled into the AVX2 translation
// unit, where any inline function
// shared with the rest of the library could be emitted with AVX2 instructions and picked by the
// linker for a CPU without them.
#include <cstdint>

namespace arcplan::collision::detail::prefilter {

// Lanes of one batch: 8 float lanes of AVX2 (the portable path computes the same 8 lanes one by one).
constexpr int kLanes = 8;
// Fixed bounds that keep the kernels' scratch space on the stack; SpherePrefilter switches itself
// off (every query goes to FCL) for a robot beyond them.
constexpr int kMaxLinks = 32;
constexpr int kMaxJoints = 32;
constexpr int kMaxBodies = 64;
constexpr int kMaxFineSpheres = 384;
constexpr int kMaxGroups = 192;

// One link of the chain: rotation in the parent frame = c0 + cos q·c1 + sin q·c2 (row-major 3×3;
// c1 = c2 = 0 for a fixed joint), translation t in the parent frame. Parents come first.
struct LinkRow {
  int parent;              // row index, -1 for the base
  int joint;               // index into q, -1 for a fixed joint
  std::uint32_t zero;      // bit i: c0[i] = c1[i] = c2[i] = 0 (the kernels skip those terms)
  std::uint32_t constant;  // bit i: c1[i] = c2[i] = 0 (entry i is c0[i] whatever q)
  // The common case of a UR chain: the origin rotation is a signed permutation (column j of it is
  // sign[j] at row column[j]) and the joint turns about a coordinate axis (axisSign · e_axis), or is
  // fixed (axis -1). Then the kernels permute the parent's columns and mix two of them.
  int permuted;  // 1: the fields below describe the rotation; 0: c0, c1, c2 only
  int column[3];
  float sign[3];
  int axis;
  float axisSign;
  float c0[9], c1[9], c2[9];
  float t[3];
  // A row no joint moves (none between it and the root, like a robot's base links): its pose in the
  // world (row-major rotation, translation), computed once in double when the tables are built, is
  // broadcast instead of recomputed (the base's two rows cost 4 % of a free-space batch).
  int fixedPose;
  float fixedR[9], fixedT[3];
};

// A group of a body's fine spheres (sphere_model.h SphereGroup): its ball (x, y, z, r in the link
// frame) and its fine spheres, rows fineBegin .. fineBegin + fineCount of the fine arrays.
struct GroupRow {
  float ball[4];
  int fineBegin, fineCount;
};

// A link with collision geometry: its coarse sphere (x, y, z, r in the link frame), its fine
// spheres (rows fineBegin .. fineBegin + fineCount of the fine arrays) in groups (rows groupBegin ..
// + groupCount of the group table; a body of one group has no ball of its own but the coarse one), the
// obstacles it is checked against (obstacleIndex[obstacleBegin .. + obstacleCount]).
struct BodyRow {
  int link;
  float coarse[4];
  int fineBegin, fineCount;
  int groupBegin, groupCount;
  int obstacleBegin, obstacleCount;
  // A body on a fixed-pose row keeps the same distance to every obstacle: those its fine spheres clear by
  // more than the margin are measured once (in double) and left out of obstacleIndex; their smallest gap
  // (not yet less the margin, kFarGap if none) starts the body's gap in the gaps kernel.
  float fixedGap;
};

// An obstacle's bounding volume: a world point p is at local = rotation·p + translation.
// kind 0: sphere of radius size[0] at the local origin; 1: box of half extents size; 2: cylinder
// along local z of radius size[0] and half length size[1].
struct ObstacleRow {
  int kind;
  int aligned;  // 1: rotation is exactly the identity
  float rotation[9];
  float translation[3];
  float size[3];
};

struct Tables {
  int dof = 0;
  int linkCount = 0, bodyCount = 0, obstacleCount = 0, selfPairCount = 0;
  const LinkRow* links = nullptr;
  const BodyRow* bodies = nullptr;
  const float *fineX = nullptr, *fineY = nullptr, *fineZ = nullptr, *fineR = nullptr;
  const GroupRow* groups = nullptr;
  const ObstacleRow* obstacles = nullptr;
  const int* obstacleIndex = nullptr;
  const int* selfPairs = nullptr;  // (body a, body b) pairs, 2 per pair
  float margin = 0.0f;             // clearance that covers every float rounding [m] (sphere_prefilter.cpp)
};

// A gap larger than any distance: "no pair measured" in the gaps kernel, and an `enough` every bound reaches.
constexpr float kFarGap = 1e30f;

// The kernels' sine and cosine take |angle| <= this (every UR joint range); larger angles are reduced
// before they reach the kernels (SpherePrefilter::loadLane).
constexpr double kLargestAngle = 2.0 * 3.14159265358979323846;

// States into lanes: state k (dof doubles at states + k * stride) into lane k of q, for k < lanes;
// the other lanes repeat state 0. false when an angle is beyond ±kLargestAngle (or NaN): the caller then
// loads those states itself. Both give the same floats (each angle rounded to nearest).
bool loadLanesPortable(const double* states, std::int64_t stride, int dof, int lanes, float* q);
bool loadLanesAvx2(const double* states, std::int64_t stride, int dof, int lanes, float* q);

// q: dof × kLanes floats, joint-major (q[j * kLanes + lane]), each |q| <= 2 pi + 1e-6.
// The lanes whose spheres are clear of every checked obstacle and every checked body pair by more
// than the margin: bit k set = lane k is free (only lanes < `lanes` are reported).
std::uint32_t freeLanesPortable(const Tables& tables, const float* q, int lanes);
std::uint32_t freeLanesAvx2(const Tables& tables, const float* q, int lanes);
// Lower bounds of the pairs' distances, already reduced by the margin: for each body its smallest
// distance to its obstacles (with BodyRow::fixedGap), then each self pair, as gaps[pair * kLanes + lane]. A pair whose
// coarse bound reaches enough[pair] in every lane keeps that bound; otherwise its groups are measured, and a group (of
// a self pair: a pair of groups) whose balls reach enough[pair] in every lane keeps their bound, the others their fine
// spheres'. A gap below enough[pair] is therefore the fine spheres' gap.
void gapsPortable(const Tables& tables, const float* q, const float* enough, float* gaps);
void gapsAvx2(const Tables& tables, const float* q, const float* enough, float* gaps);

}  // namespace arcplan::collision::detail::prefilter
