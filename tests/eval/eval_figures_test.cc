#include "eval/eval_figures.h"

#include <gtest/gtest.h>

namespace fleetmap::eval {
namespace {

TEST(EvalFiguresTest, AnActorMappedForAWhileIsAnActorNotAFalseRemoval) {
  OverlayCell walked;
  walked.actor_swept = true;
  walked.ever_occupied = true;  // mapped while a person stood there, removed again
  EXPECT_EQ(ClassifyOverlayCell(walked), OverlayClass::kActorMapped);
  walked.occupied = true;  // still in the final map
  EXPECT_EQ(ClassifyOverlayCell(walked), OverlayClass::kActorMapped);
  walked.actor_swept = false;  // the same cell where no actor went: a false addition
  EXPECT_EQ(ClassifyOverlayCell(walked), OverlayClass::kFalseAdded);
  OverlayCell removed_for_nothing;
  removed_for_nothing.ever_occupied = true;
  EXPECT_EQ(ClassifyOverlayCell(removed_for_nothing), OverlayClass::kFalseRemoval);
}

TEST(EvalFiguresTest, APalletWhereAPersonWalkedBeforeIsStillAnAddition) {
  OverlayCell pallet;
  pallet.actor_swept = true;
  pallet.true_added = true;
  pallet.occupied = true;
  EXPECT_EQ(ClassifyOverlayCell(pallet), OverlayClass::kAddedOk);
  pallet.occupied = false;
  EXPECT_EQ(ClassifyOverlayCell(pallet), OverlayClass::kMissed);
  pallet.seen_free_near = true;  // a vehicle reported it free and it was dropped
  EXPECT_EQ(ClassifyOverlayCell(pallet), OverlayClass::kMissedSeenFree);
  pallet.occupied = true;  // mapped again later
  EXPECT_EQ(ClassifyOverlayCell(pallet), OverlayClass::kAddedOk);
  OverlayCell wall;
  wall.is_static = true;
  EXPECT_EQ(ClassifyOverlayCell(wall), OverlayClass::kWallErased);
  wall.occupied = true;
  EXPECT_EQ(ClassifyOverlayCell(wall), OverlayClass::kNone);
}

}  // namespace
}  // namespace fleetmap::eval
