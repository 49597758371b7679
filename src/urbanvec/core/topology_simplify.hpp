// Topology-preserving Douglas–Peucker simplification of one polygon (issue 21): the algorithm of
// GEOS 3.11's TopologyPreservingSimplifier (JTS's TaggedLineStringSimplifier) for a single polygon,
// in plain code on core geometry, so the parcel search (spec §3 E2, which simplifies every new parcel
// before it looks for its road-facing edges) does not pay for a GEOS geometry, two quadtrees and a
// line intersector per parcel.
//
// Same rules as GEOS: every ring is simplified in turn (the outer ring, then the holes), a section
// i..j of a ring is replaced by its chord when every vertex in between lies within the tolerance of it,
// when the ring keeps at least 4 points in the worst case, and when the chord meets no remaining input
// segment of any ring (outside the section itself) and no chord kept so far except at shared ends;
// otherwise the section is split at its farthest vertex. Rings keep their first point.
#pragma once

#include "urbanvec/core/geometry.hpp"

namespace urbanvec {

/// The polygon simplified with the given distance tolerance (>= 0), its rings' topology kept: no ring
/// crosses itself or another, none collapses below 4 points. Rings with fewer than 4 points are
/// copied unchanged.
Polygon simplifyPreservingTopology(const Polygon& polygon, double tolerance);
/// The same into `out`, whose rings' memory is reused; the work lists are reused per thread (the
/// parcel search simplifies every new parcel, issue 21).
void simplifyPreservingTopology(const Polygon& polygon, double tolerance, Polygon& out);

/// True when the closed segments p0p1 and q0q1 share a point other than one common end point of both
/// (GEOS's "interior intersection": a crossing, an end on the other's interior, a collinear overlap
/// other than the identical segment). Exact orientation signs.
bool segmentsMeetInside(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1);

}  // namespace urbanvec
