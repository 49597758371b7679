// Every parameter of the shrinking pipeline with the thesis's defaults (spec §B.12), plus the options
// for the choices the thesis leaves open (§B.10 seam order, §B.11 straightening, rotation, full map).
#pragma once

#include <map>
#include <string>

namespace urbanvec::shrink {

enum class SeamOrder {
  Interleaved,  ///< one vertical, one horizontal, ... then the rest of the longer list
  Blocks        ///< all vertical seams, then all horizontal seams
};

enum class LandmarkFreeze {
  BoundingBox,  ///< every pixel of each landmark element's pixel bounding box: a pure translation
  Nodes         ///< only the pixels holding landmark nodes (the thesis, §B.9 item 6)
};

struct CleaningOptions {
  /// §B.2 "remove segments outside bounding box": drop nodes outside the download bounds (and the
  /// segments with them); enabled in the thesis.
  bool removeOutsideBounds = true;
};

struct SelectionOptions {
  /// proxStrThreshold, metres: the thesis's 0.00033 degrees of latitude (§B.3) is 36.7 m.
  double proximityThreshold = 36.7;
  /// highwayWeights_d (§B.12); strT = weight / 10 (§B.4 [INFERENCE]).
  std::map<std::string, double> highwayWeights = {
      {"motorway", 3.0}, {"primary", 2.5}, {"secondary", 2.0}, {"tertiary", 1.5}, {"residential", 1.0}};
  /// Weight of any other or missing highway value (strT 0.05, §B.4).
  double otherHighwayWeight = 0.5;
  /// Factor of the intersection-count term and of the length term (§B.4: 0.1 each).
  double intersectionFactor = 0.1;
  double lengthFactor = 0.1;
  /// Important streets get importantBase + (1 - importantBase) * appearW (§B.4: 0.5 + 0.5 appearW).
  double importantBase = 0.5;
  /// shF, fraction of streets kept (§B.4); round(shF * #streets) streets are selected.
  double shrinkFactor = 0.2;
};

struct ConnectionOptions {
  /// impDistBalance, alpha of the A* cost alpha * d / impW + (1 - alpha) * d (§B.5): 1 = importance
  /// only, 0 = distance only (the formula's convention; the thesis's prose states the reverse).
  double impDistBalance = 0.5;
  /// noImpClusters (§B.5): delete clusters still disconnected that hold no important place.
  bool removeUnimportantClusters = true;
  /// m-degree (§B.6): the most street segments a dead-end connection may have (thesis default 3; the
  /// Firenze figure uses 10).
  int mDegree = 3;
};

struct CarvingOptions {
  /// imageSize (§B.8): the larger raster dimension, pixels.
  int imageSize = 500;
  /// grayDistBalance (§B.10): energy = b * inverted gray + (1 - b) * inverted distance field.
  double grayDistBalance = 0.5;
  /// imageSizeReduction (§B.12): vertical seams (remove columns) and horizontal seams (remove rows).
  int verticalSeams = 100;
  int horizontalSeams = 100;
  SeamOrder order = SeamOrder::Blocks;
  /// Which landmark pixels get +infinite energy (§B.9 item 6; §B.14 "freeze whole important areas").
  LandmarkFreeze landmarkFreeze = LandmarkFreeze::BoundingBox;
  /// Freeze the pixel of every skeleton street node, not only intersections and ends (§B.11: the
  /// thesis's fix for lost curvature).
  bool freezeAllStreetNodes = false;
  /// Keep non-frozen skeleton nodes whose pixel a seam removes (collapsed onto the seam's edge)
  /// instead of deleting them from their ways (§B.11 deletes them).
  bool keepCarvedNodes = false;
  /// Back to vector (§B.11): densify every skeleton way so consecutive points are at most this many
  /// pixels apart before carving, so a way follows the carved raster instead of keeping straight
  /// segments between distant nodes (which fold over nearby ways); 0 = the thesis (nodes only).
  double densifySpacing = 1.0;
  /// After carving, a synthetic point (or a node whose pixel was removed) is dropped only when the
  /// shortcut stays within this many pixels of the points it replaces and touches no other segment.
  double simplifyTolerance = 1.0;
  /// Crossing guard: before a seam is removed it is applied to the densified ways; when two way segments
  /// would then cross or touch, the seam's pixels on their lines get +infinity and the seam is searched
  /// again (only the pixels where a crossing would really arise are frozen).
  bool separateWays = true;
  /// Threads of seam carving (0 = every core); the output does not depend on it.
  int threads = 0;
};

struct PostOptions {
  /// §B.11 stretching: re-straighten ways that were straight in the original.
  bool straighten = false;
  /// A way is straight when every interior node lies within this distance of its chord, metres.
  double straightTolerance = 2.0;
  /// Rounds of the straightening relaxation (nodes shared by straight ways get the mean target).
  int straightenRounds = 20;
  /// Rotation trick (§B.11, §4.6.1), degrees counter-clockwise about the bounding-box centre before
  /// carving (undone afterwards); ignored when autoRotate.
  double rotationDegrees = 0.0;
  /// Rotate by minus the dominant street bearing (length-weighted, modulo 90 degrees) so the main grid
  /// direction is axis-aligned.
  bool autoRotate = false;
  /// Deform the full street map with the same seams (§B.14), for the `full_streets` layer.
  bool fullMap = true;
};

struct ShrinkOptions {
  CleaningOptions cleaning;
  SelectionOptions selection;
  ConnectionOptions connection;
  CarvingOptions carving;
  PostOptions post;
};

/// Checks the ranges (shF and balances in [0, 1], imageSize > 1, mDegree >= 1, seams >= 0, weights
/// >= 0); throws an InvalidOption error naming the thesis parameter.
void validate(const ShrinkOptions& options);

}  // namespace urbanvec::shrink
