#include "evidence/colour_model.h"

#include <cmath>

#include <gtest/gtest.h>

namespace movseg {
namespace {

const cv::Vec3b kRed(0, 0, 255), kGreen(0, 255, 0), kBlue(255, 0, 0);

// Three vertical stripes of 16 x 32 pixels: red, green, blue.
cv::Mat stripes() {
  cv::Mat bgr(32, 48, CV_8UC3);
  bgr.colRange(0, 16).setTo(cv::Scalar(kRed[0], kRed[1], kRed[2]));
  bgr.colRange(16, 32).setTo(cv::Scalar(kGreen[0], kGreen[1], kGreen[2]));
  bgr.colRange(32, 48).setTo(cv::Scalar(kBlue[0], kBlue[1], kBlue[2]));
  return bgr;
}

cv::Mat stripeEvidence(float red, float green, float blue) {
  cv::Mat evidence(32, 48, CV_32F);
  evidence.colRange(0, 16).setTo(red);
  evidence.colRange(16, 32).setTo(green);
  evidence.colRange(32, 48).setTo(blue);
  return evidence;
}

// The colour evidence ColourModel adds at the first pixel of each stripe.
cv::Vec3f colourEvidence(const ColourModel& model, const cv::Mat& bgr) {
  cv::Mat with_colour;
  model.addEvidence(bgr, cv::Mat::zeros(bgr.size(), CV_32F), &with_colour);
  return {with_colour.at<float>(0, 0), with_colour.at<float>(0, 16), with_colour.at<float>(0, 32)};
}

// A model that has seen one frame of stripes(), memory saying nothing.
ColourModel learntFrom(const Params& params, const cv::Mat& evidence) {
  ColourModel model(params);
  model.update(stripes(), evidence, evidence);
  return model;
}

TEST(ColourModel, LearnsTheColoursOfConfidentPixelsOnly) {
  const Params params;
  // Red moves, green is undecided, blue is static.
  const ColourModel model = learntFrom(params, stripeEvidence(2.5f, 0.5f, -2.5f));
  const cv::Vec3f colour = colourEvidence(model, stripes());
  const auto most = static_cast<float>(params.colour_weight * params.colour_clip);
  EXPECT_FLOAT_EQ(colour[0], most);
  EXPECT_FLOAT_EQ(colour[1], 0.f);  // seen by neither histogram
  // Against a mover at most log 4: the next mover may show the background's colours.
  EXPECT_FLOAT_EQ(colour[2], static_cast<float>(params.colour_weight) * std::log(0.25f));
}

// Blue is the background's only colour and no mover has shown it. However long that is seen,
// a new mover in blue pays at most colour_weight * log 4 (1.73) for it, not the full clip's
// 2.5 (colour_clip 2 x 1.25); a narrower colour_clip still bounds both sides.
TEST(ColourModel, AMoverInTheBackgroundsColoursIsNotRuledOutByThem) {
  const Params params;
  const cv::Mat red_moves = stripeEvidence(2.5f, -2.5f, -2.5f);
  ColourModel model(params);
  for (int frame = 0; frame < 30; ++frame) model.update(stripes(), red_moves, red_moves);
  const auto weight = static_cast<float>(params.colour_weight);
  EXPECT_NEAR(colourEvidence(model, stripes())[2], -weight * std::log(4.f), 1e-5);
  // A narrower clip is kept.
  Params narrow;
  narrow.colour_clip = 0.5;
  const ColourModel clipped = learntFrom(narrow, red_moves);
  EXPECT_FLOAT_EQ(colourEvidence(clipped, stripes())[2], -0.5f * weight);
}

// Red was taken for a mover; now every pair says it is static as strongly as a pair can (the
// evidence floor), but it lies inside the carried mask, whose memory raises its evidence above
// -colour_confidence. Green moves. The pair's own verdict teaches the background red, so red's
// colour evidence turns from moving to static; without colour_forgetting red stays moving.
TEST(ColourModel, WhatThePairCallsStaticIsLearntAsBackgroundDespiteMemory) {
  const Params params;
  const cv::Mat bgr = stripes();
  const cv::Mat first = stripeEvidence(2.5f, 2.5f, -2.5f);
  ColourModel model = learntFrom(params, first);
  ASSERT_GT(colourEvidence(model, bgr)[0], 0.f);

  const auto floor = static_cast<float>(params.evidence_min);
  const cv::Mat pair = stripeEvidence(floor, 2.5f, floor);
  const cv::Mat with_memory = stripeEvidence(floor + 0.69f, 2.5f, floor - 0.69f);
  for (int frame = 0; frame < 30; ++frame) model.update(bgr, with_memory, pair);
  const cv::Vec3f colour = colourEvidence(model, bgr);
  EXPECT_LT(colour[0], -1.f);
  EXPECT_GT(colour[1], 2.f);

  Params keeps = params;
  keeps.colour_forgetting = 0;
  ColourModel memory_only = learntFrom(keeps, first);
  for (int frame = 0; frame < 30; ++frame) memory_only.update(bgr, with_memory, pair);
  EXPECT_GT(colourEvidence(memory_only, bgr)[0], 2.f);
}

// A slow mover, red: its edge (4 of its 16 columns) moves, its still inside, inside the carried
// mask, looks static to the pair. Counted at a quarter, the inside does not outweigh the edge,
// and red stays a mover's colour; counted in full, red would turn to background.
TEST(ColourModel, ASlowMoversStillInsideDoesNotTeachAwayItsColour) {
  const cv::Mat bgr = stripes();
  const auto floor = static_cast<float>(Params().evidence_min);
  cv::Mat pair = stripeEvidence(floor, 2.5f, floor);
  pair.colRange(0, 4).setTo(2.5f);
  cv::Mat with_memory = stripeEvidence(floor + 0.69f, 2.5f, floor - 0.69f);
  with_memory.colRange(0, 4).setTo(2.5f);
  auto redAfterThirtyFrames = [&](double forgetting) {
    Params params;
    params.colour_forgetting = forgetting;
    ColourModel model(params);
    for (int frame = 0; frame < 30; ++frame) model.update(bgr, with_memory, pair);
    return colourEvidence(model, bgr)[0];
  };
  EXPECT_GT(redAfterThirtyFrames(Params().colour_forgetting), 0.f);
  EXPECT_LT(redAfterThirtyFrames(1.0), 0.f);
}

// Red is a mover's colour (the top of its stripe moves) and the background's too (its bottom
// is static); then nothing moves for 60 frames, the top of red undecided. Unseen, the movers'
// colours fade into the background's, and red's colour evidence with them; kept as last
// learnt, red would still pull into the mask whatever shows it.
TEST(ColourModel, TheMoversColoursFadeWhenNoMoverIsSeen) {
  const Params params;
  const cv::Mat bgr = stripes();
  cv::Mat first = stripeEvidence(2.5f, -2.5f, -2.5f);
  first(cv::Rect(0, 16, 16, 16)).setTo(-2.5f);
  const ColourModel model = learntFrom(params, first);
  const float learnt = colourEvidence(model, bgr)[0];
  ASSERT_GT(learnt, 1.f);

  ColourModel unseen = model;
  cv::Mat still = stripeEvidence(0.5f, -2.5f, -2.5f);
  still(cv::Rect(0, 16, 16, 16)).setTo(-2.5f);
  for (int frame = 0; frame < 60; ++frame) unseen.update(bgr, still, still);
  EXPECT_LT(colourEvidence(unseen, bgr)[0], 0.25f * learnt);
  EXPECT_GE(colourEvidence(unseen, bgr)[0], 0.f);
}

// Red moves at the left of the view and is static at the right, green is static between: 160 x
// 80 pixels, columns of 40 (cells of 40 x 40, two rows of four). Seen over the frame, red is
// the mover's colour wherever it shows (the movers show nothing else); in the right-hand cells,
// which have seen it static only, it says little; in the green cells, which never saw it as
// background, it says more than over the frame.
TEST(ColourModel, AColourMeansWhatItMeansWhereItIsSeen) {
  cv::Mat bgr(80, 160, CV_8UC3, cv::Scalar(kGreen[0], kGreen[1], kGreen[2]));
  bgr.colRange(0, 40).setTo(cv::Scalar(kRed[0], kRed[1], kRed[2]));
  bgr.colRange(120, 160).setTo(cv::Scalar(kRed[0], kRed[1], kRed[2]));
  cv::Mat evidence(bgr.size(), CV_32F, cv::Scalar(-2.5f));
  evidence.colRange(0, 40).setTo(2.5f);
  const cv::Mat all_red(bgr.size(), CV_8UC3, cv::Scalar(kRed[0], kRed[1], kRed[2]));
  auto redEvidence = [&](int cell_side) {  // at the left, the middle and the right
    Params params;
    params.colour_cell = cell_side;
    ColourModel model(params);
    for (int frame = 0; frame < 10; ++frame) model.update(bgr, evidence, evidence);
    cv::Mat with_colour;
    model.addEvidence(all_red, cv::Mat::zeros(bgr.size(), CV_32F), &with_colour);
    return cv::Vec3f(with_colour.at<float>(60, 20), with_colour.at<float>(60, 80),
                     with_colour.at<float>(60, 140));
  };
  const cv::Vec3f frame = redEvidence(0);
  EXPECT_NEAR(frame[0], 1.368f, 0.001f);  // 1.25 log(0.996 / (1/3)): p_fg with its prior
  EXPECT_EQ(frame[1], frame[0]);
  EXPECT_EQ(frame[2], frame[0]);
  const cv::Vec3f cells = redEvidence(40);
  EXPECT_NEAR(cells[0], frame[0], 0.01f);  // the mover's cells saw no background: the frame's
  EXPECT_GT(cells[1], 2.f);   // never background there
  EXPECT_LT(cells[2], 0.25f);  // the background's colour there
  EXPECT_GT(cells[2], 0.f);    // the movers the frame has seen are red: the cell's prior
}

// Red at level 208 moves at the left; red at level 192, in the same cell bin (3 bits a channel)
// but another of the frame's bins (4 bits), is static at the right, green static between; the
// cells of the middle see nothing confident. 160 x 80 pixels, cells of 40 x 40. The right-hand
// cells learnt their cell bin as the background's, yet the frame's finer histograms still tell
// the mover's red apart there: full say for it (a cell's say alone, 1.25 log(1.00 / 0.88) =
// 0.15), none for the static red. Where the cells saw nothing, the frame's say, to the float.
TEST(ColourModel, ColoursThatShareACellBinAreToldApartByTheFrame) {
  const cv::Scalar red208(0, 0, 208), red192(0, 0, 192);
  cv::Mat bgr(80, 160, CV_8UC3, cv::Scalar(kGreen[0], kGreen[1], kGreen[2]));
  bgr.colRange(0, 40).setTo(red208);
  bgr.colRange(120, 160).setTo(red192);
  cv::Mat evidence(bgr.size(), CV_32F, cv::Scalar(-2.5f));
  evidence.colRange(0, 40).setTo(2.5f);
  evidence.colRange(80, 120).setTo(0.f);
  auto evidenceOf = [&](const cv::Scalar& colour, int cell_side) {  // in the middle, the right
    Params params;
    params.colour_cell = cell_side;
    ColourModel model(params);
    for (int frame = 0; frame < 10; ++frame) model.update(bgr, evidence, evidence);
    cv::Mat with_colour;
    model.addEvidence(cv::Mat(bgr.size(), CV_8UC3, colour),
                      cv::Mat::zeros(bgr.size(), CV_32F), &with_colour);
    return cv::Vec2f(with_colour.at<float>(60, 100), with_colour.at<float>(60, 140));
  };
  const Params params;
  const auto most = static_cast<float>(params.colour_weight * params.colour_clip);
  const auto least = static_cast<float>(params.colour_weight * std::log(0.25));
  EXPECT_FLOAT_EQ(evidenceOf(red208, 40)[1], most);
  EXPECT_FLOAT_EQ(evidenceOf(red192, 40)[1], least);
  for (const cv::Scalar& colour : {red208, red192, cv::Scalar(kGreen[0], kGreen[1], kGreen[2])})
    EXPECT_NEAR(evidenceOf(colour, 40)[0], evidenceOf(colour, 0)[0], 1e-5f);
}

// Cells of one pixel with 5 bits a channel (4 in a cell) would want 40,000 x 4,096 bins at 200
// x 200: the cells grow until their tables fit (1 MB each), and the model still tells the
// stripes' colours.
TEST(ColourModel, CellsTooSmallForTheirTablesGrow) {
  Params params;
  params.colour_cell = 1;
  params.colour_bits = 5;
  cv::Mat bgr(200, 200, CV_8UC3, cv::Scalar(kBlue[0], kBlue[1], kBlue[2]));
  bgr.colRange(0, 100).setTo(cv::Scalar(kRed[0], kRed[1], kRed[2]));
  cv::Mat evidence(bgr.size(), CV_32F, cv::Scalar(-2.5f));
  evidence.colRange(0, 100).setTo(2.5f);
  ColourModel model(params);
  model.update(bgr, evidence, evidence);
  cv::Mat with_colour;
  model.addEvidence(bgr, cv::Mat::zeros(bgr.size(), CV_32F), &with_colour);
  EXPECT_GT(with_colour.at<float>(100, 50), 2.f);
  EXPECT_LT(with_colour.at<float>(100, 150), -1.f);
}

// Bins worked out sixteen pixels at a time (rowBins) are those of the per-pixel tables: a
// model learning from a frame and a model learning from the same pixels as one column (one
// pixel per row: all looked up) add the same colour evidence to the bit, at every bin size.
TEST(ColourModel, BinsOfWideRowsAreThoseOfSinglePixels) {
  cv::RNG rng(7);
  for (int bits = 1; bits <= 5; ++bits) {
    Params params;
    params.colour_bits = bits;
    params.colour_cell = 0;  // one histogram for any shape of frame
    cv::Mat bgr(24, 53, CV_8UC3), evidence(bgr.size(), CV_32F);
    rng.fill(bgr, cv::RNG::UNIFORM, 0, 256);
    rng.fill(evidence, cv::RNG::UNIFORM, -3.f, 3.f);
    const cv::Mat column_bgr = bgr.reshape(0, static_cast<int>(bgr.total()));
    const cv::Mat column_evidence = evidence.reshape(0, static_cast<int>(evidence.total()));
    ColourModel wide(params), narrow(params);
    wide.update(bgr, evidence, evidence);
    narrow.update(column_bgr, column_evidence, column_evidence);
    cv::Mat from_wide, from_narrow;
    wide.addEvidence(bgr, evidence, &from_wide);
    narrow.addEvidence(column_bgr, column_evidence, &from_narrow);
    const cv::Mat wide_as_column = from_wide.reshape(0, static_cast<int>(bgr.total()));
    EXPECT_EQ(cv::norm(wide_as_column, from_narrow, cv::NORM_INF), 0) << bits << " bits";
    EXPECT_NE(cv::norm(from_wide, evidence, cv::NORM_INF), 0) << "colour said nothing";
  }
}

}  // namespace
}  // namespace movseg
