// The rules of a run (problems/game.hpp): legal pots, fouls on the wrong first contact,
// snooker's re-spotting, the 8 potted early, and layouts' errors naming the field.
// Strokes are judged from outcomes written by hand, so that each rule is tested alone.
#include "cueplan/problems/game.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

namespace phys = cueplan::physics;
namespace prob = cueplan::problems;

phys::Scene scene_with(std::vector<phys::ObjectBall> balls) {
  phys::Scene scene = phys::snooker_scene();
  scene.balls = std::move(balls);
  return scene;
}

// An outcome: the cue ball at rest at (1, 1), struck `first` first (-1: none), the balls
// named in `potted` (with their pockets) dropped, the others where they were.
phys::ShotResult outcome(const phys::Scene& scene, const std::string& first,
                         const std::vector<std::pair<std::string, int>>& potted) {
  phys::ShotResult r;
  r.status = phys::ShotStatus::rest;
  r.final_position = {1.0, 1.0};
  phys::BallOutcome cue;
  cue.name = phys::kCueBallName;
  cue.final_position = r.final_position;
  r.balls.push_back(cue);
  for (const phys::ObjectBall& b : scene.balls) {
    phys::BallOutcome o;
    o.name = b.name;
    o.start = o.final_position = b.position;
    for (const auto& [name, pocket] : potted)
      if (name == b.name) {
        o.pocketed = true;
        o.pocket = pocket;
      }
    if (b.name == first) r.first_contact = static_cast<int>(r.balls.size());
    r.balls.push_back(o);
  }
  return r;
}

TEST(GameTest, NamesRoundTrip) {
  for (const char* name : prob::kGameNames) {
    prob::Game g;
    ASSERT_TRUE(prob::parse_game(name, &g));
    EXPECT_STREQ(prob::to_string(g), name);
  }
  prob::Game g;
  EXPECT_FALSE(prob::parse_game("ten_ball", &g));
  prob::Group group;
  EXPECT_TRUE(prob::parse_group("stripes", &group));
  EXPECT_EQ(group, prob::Group::stripes);
  EXPECT_FALSE(prob::parse_group("open", &group));
}

TEST(GameTest, NineBallOnlyTheLowestIsOnAndTheWrongFirstContactIsAFoul) {
  const phys::Scene scene = scene_with({{"9", {2.0, 1.0}}, {"7", {1.5, 0.5}}, {"6", {2.5, 0.5}}});
  const prob::GameState s = prob::initial_state(prob::Game::nine_ball, std::nullopt);
  EXPECT_EQ(prob::balls_on(s, scene.balls), std::vector<std::string>{"6"});
  const prob::ShotJudgement foul = prob::judge_stroke(s, scene, {"6", 0}, outcome(scene, "7", {{"6", 0}}));
  EXPECT_FALSE(foul.continues);
  EXPECT_TRUE(foul.foul);
  EXPECT_EQ(foul.reason, "foul: struck 7 first");
  const prob::ShotJudgement ok = prob::judge_stroke(s, scene, {"6", 0}, outcome(scene, "6", {{"6", 0}}));
  EXPECT_TRUE(ok.continues);
  EXPECT_FALSE(ok.next.cleared);
  EXPECT_EQ(ok.balls.size(), 2u);
  EXPECT_EQ(prob::balls_on(ok.next, ok.balls), std::vector<std::string>{"7"});
}

TEST(GameTest, NineBallACombinationOnTheNineWins) {
  const phys::Scene scene = scene_with({{"9", {2.0, 1.0}}, {"7", {1.5, 0.5}}});
  const prob::GameState s = prob::initial_state(prob::Game::nine_ball, std::nullopt);
  const prob::ShotJudgement j = prob::judge_stroke(s, scene, {"7", 2}, outcome(scene, "7", {{"9", 5}}));
  EXPECT_TRUE(j.continues);
  EXPECT_TRUE(j.next.cleared);
  // The same drop after striking the 9 first is a foul.
  EXPECT_TRUE(prob::judge_stroke(s, scene, {"7", 2}, outcome(scene, "9", {{"9", 5}})).foul);
}

TEST(GameTest, MissesAndTheCueBallPottedEndTheRun) {
  const phys::Scene scene = scene_with({{"1", {2.0, 1.0}}, {"2", {1.5, 0.5}}});
  const prob::GameState s = prob::initial_state(prob::Game::any_order, std::nullopt);
  const prob::ShotJudgement miss = prob::judge_stroke(s, scene, {"1", 0}, outcome(scene, "1", {}));
  EXPECT_FALSE(miss.continues);
  EXPECT_FALSE(miss.foul);
  EXPECT_EQ(miss.reason, "missed the pot");
  phys::ShotResult in_off = outcome(scene, "1", {{"1", 0}});
  in_off.status = phys::ShotStatus::pocketed;
  EXPECT_EQ(prob::judge_stroke(s, scene, {"1", 0}, in_off).reason, "foul: cue ball potted");
  EXPECT_EQ(prob::judge_stroke(s, scene, {"1", 0}, outcome(scene, "", {})).reason, "foul: struck no ball");
  // any_order: either ball first; both dropping clears.
  const prob::ShotJudgement both = prob::judge_stroke(s, scene, {"1", 0}, outcome(scene, "2", {{"1", 0}, {"2", 3}}));
  EXPECT_TRUE(both.continues);
  EXPECT_TRUE(both.next.cleared);
  EXPECT_EQ(both.next.potted, 2);
}

TEST(GameTest, EightBallTheEightEarlyLosesAndTheCalledPocketCounts) {
  const phys::Scene scene = scene_with({{"8", {2.0, 1.0}}, {"1", {1.5, 0.5}}, {"12", {2.5, 0.5}}});
  const prob::GameState s = prob::initial_state(prob::Game::eight_ball, prob::Group::solids);
  EXPECT_EQ(prob::balls_on(s, scene.balls), std::vector<std::string>{"1"});
  const prob::ShotJudgement early = prob::judge_stroke(s, scene, {"1", 0}, outcome(scene, "1", {{"1", 0}, {"8", 2}}));
  EXPECT_FALSE(early.continues);
  EXPECT_TRUE(early.foul);
  EXPECT_EQ(early.reason, "the 8 potted early");
  EXPECT_TRUE(prob::judge_stroke(s, scene, {"1", 0}, outcome(scene, "12", {{"1", 0}})).foul);
  // Their ball alone: the run ends without a foul.
  EXPECT_FALSE(prob::judge_stroke(s, scene, {"1", 0}, outcome(scene, "1", {{"12", 0}})).continues);

  // The group cleared: the 8 is on, and must drop in the called pocket.
  const phys::Scene last = scene_with({{"8", {2.0, 1.0}}, {"12", {2.5, 0.5}}});
  EXPECT_EQ(prob::balls_on(s, last.balls), std::vector<std::string>{"8"});
  const prob::ShotJudgement win = prob::judge_stroke(s, last, {"8", 5}, outcome(last, "8", {{"8", 5}}));
  EXPECT_TRUE(win.continues);
  EXPECT_TRUE(win.next.cleared);
  const prob::ShotJudgement wrong = prob::judge_stroke(s, last, {"8", 5}, outcome(last, "8", {{"8", 2}}));
  EXPECT_FALSE(wrong.continues);
  EXPECT_EQ(wrong.reason, "the 8 in the wrong pocket");
}

TEST(GameTest, EightBallAnOpenTableTakesTheGroupOfTheFirstPot) {
  const phys::Scene scene = scene_with({{"8", {2.0, 1.0}}, {"3", {1.5, 0.5}}, {"12", {2.5, 0.5}}});
  const prob::GameState s = prob::initial_state(prob::Game::eight_ball, std::nullopt);
  EXPECT_EQ(prob::balls_on(s, scene.balls).size(), 2u);
  const prob::ShotJudgement j = prob::judge_stroke(s, scene, {"12", 0}, outcome(scene, "12", {{"12", 0}}));
  EXPECT_TRUE(j.continues);
  EXPECT_EQ(j.next.group, prob::Group::stripes);
  EXPECT_EQ(prob::balls_on(j.next, j.balls), std::vector<std::string>{"8"});
}

TEST(GameTest, SnookerRedThenColourAndTheColourIsRespotted) {
  const phys::Scene scene = scene_with({{"red", {2.9, 1.2}}, {"red2", {3.0, 0.4}}, {"pink", {2.0, 0.3}}, {"black", {2.2, 1.5}}});
  prob::GameState s = prob::initial_state(prob::Game::snooker, std::nullopt);
  EXPECT_EQ(prob::balls_on(s, scene.balls), (std::vector<std::string>{"red", "red2"}));
  // A colour first while a red is on: foul.
  EXPECT_TRUE(prob::judge_stroke(s, scene, {"red", 5}, outcome(scene, "pink", {{"red", 5}})).foul);
  const prob::ShotJudgement red = prob::judge_stroke(s, scene, {"red", 5}, outcome(scene, "red", {{"red", 5}}));
  ASSERT_TRUE(red.continues);
  EXPECT_EQ(red.points, 1);
  EXPECT_TRUE(red.next.colour_on);
  EXPECT_EQ(prob::balls_on(red.next, red.balls), (std::vector<std::string>{"pink", "black"}));

  // The pink nominated and potted: back on its spot, 6 points, a red on again.
  const phys::Scene after = scene_with(red.balls);
  const prob::ShotJudgement pink = prob::judge_stroke(red.next, after, {"pink", 0}, outcome(after, "pink", {{"pink", 0}}));
  ASSERT_TRUE(pink.continues);
  EXPECT_EQ(pink.points, 6);
  EXPECT_FALSE(pink.next.colour_on);
  EXPECT_EQ(pink.next.score, 7);
  bool found = false;
  for (const phys::ObjectBall& b : pink.balls)
    if (b.name == "pink") {
      found = true;
      EXPECT_NEAR(b.position.x, prob::colour_spot(after, 6).x, 1e-12);
      EXPECT_NEAR(b.position.y, prob::colour_spot(after, 6).y, 1e-12);
    }
  EXPECT_TRUE(found);
  // Another colour dropping with the nominated one: foul.
  EXPECT_TRUE(prob::judge_stroke(red.next, after, {"pink", 0},
                                 outcome(after, "pink", {{"pink", 0}, {"black", 3}})).foul);
}

TEST(GameTest, SnookerARespottedColourTakesTheHighestFreeSpotWhenItsOwnIsTaken) {
  const phys::Scene base = phys::snooker_scene();
  // Its own spot covered by a red, the black on its spot: the pink goes to the blue's.
  std::vector<phys::ObjectBall> balls = {{"red", prob::colour_spot(base, 6)},
                                         {"black", prob::colour_spot(base, 7)},
                                         {"pink", {1.0, 0.3}}};
  prob::GameState s = prob::initial_state(prob::Game::snooker, std::nullopt);
  s.colour_on = true;
  const prob::GameState next = prob::after_pot(s, base, "pink", &balls);
  EXPECT_FALSE(next.colour_on);
  ASSERT_EQ(balls.size(), 3u);
  EXPECT_EQ(balls.back().name, "pink");
  EXPECT_NEAR(balls.back().position.x, prob::colour_spot(base, 5).x, 1e-12);
}

TEST(GameTest, SnookerTheColoursInOrderOnceTheRedsAreGone) {
  const phys::Scene scene = scene_with({{"black", {3.2, 0.9}}, {"blue", {1.78, 0.9}}, {"pink", {2.6, 0.9}}});
  const prob::GameState s = prob::initial_state(prob::Game::snooker, std::nullopt);
  EXPECT_EQ(prob::balls_on(s, scene.balls), std::vector<std::string>{"blue"});
  EXPECT_TRUE(prob::judge_stroke(s, scene, {"blue", 1}, outcome(scene, "pink", {{"blue", 1}})).foul);
  const prob::ShotJudgement blue = prob::judge_stroke(s, scene, {"blue", 1}, outcome(scene, "blue", {{"blue", 1}}));
  EXPECT_TRUE(blue.continues);
  EXPECT_EQ(blue.balls.size(), 2u);  // not re-spotted
  EXPECT_EQ(blue.points, 5);
}

const char* kLayout = R"(name: test layout
balls:
  "1": [1.0, 0.5]
  "9": [2.0, 1.0]
cue_ball: [0.5, 0.5]
)";

TEST(GameTest, LayoutFieldsAreRead) {
  const prob::LayoutResult r = prob::parse_layout(std::string("game: nine_ball\n") + kLayout, "t.yaml");
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.layout->game, prob::Game::nine_ball);
  EXPECT_FALSE(r.layout->group.has_value());
  EXPECT_FALSE(r.layout->problem.has_target);
  EXPECT_FALSE(r.layout->problem.pot.has_value());
  EXPECT_EQ(r.layout->problem.scene.balls.size(), 2u);
}

TEST(GameTest, LayoutErrorsNameTheField) {
  const auto error_of = [](const std::string& text) {
    const prob::LayoutResult r = prob::parse_layout(text, "t.yaml");
    EXPECT_FALSE(r.ok());
    return r.error;
  };
  EXPECT_EQ(error_of(std::string("game: ten_ball\n") + kLayout),
            "t.yaml:1: game: must be any_order, nine_ball, eight_ball or snooker, got 'ten_ball'");
  EXPECT_EQ(error_of(std::string("game: nine_ball\ngroup: spots\n") + kLayout),
            "t.yaml:2: group: must be solids or stripes, got 'spots'");
  EXPECT_NE(error_of(std::string("game: nine_ball\ngroup: solids\n") + kLayout).find("group: is for eight_ball only"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kLayout) + "pot: {ball: \"1\", pocket: top_left}\n").find("t.yaml:6: pot: a layout has no pot"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kLayout) + "target: [1, 1]\n").find("target: a layout has no target"),
            std::string::npos);
  EXPECT_NE(error_of("game: snooker\nballs:\n  red: [1, 1]\n  \"7\": [2, 1]\ncue_ball: [0.5, 0.5]\n")
                .find("t.yaml:2: balls.7: is not a snooker ball"),
            std::string::npos);
  EXPECT_NE(error_of("game: eight_ball\nballs:\n  \"1\": [1, 1]\ncue_ball: [0.5, 0.5]\n").find("eight_ball needs the 8"),
            std::string::npos);
  // The loader's own errors keep their lines.
  EXPECT_NE(error_of("game: any_order\nballs:\n  \"1\": [1, 1]\ncue_ball: [9.5, 0.5]\n").find("t.yaml:4: cue_ball"),
            std::string::npos);
}

TEST(GameTest, ShippedLayoutsLoad) {
  for (const char* stem : {"any_order_three", "nine_ball_four", "eight_ball_solids", "snooker_colours"}) {
    const prob::LayoutResult r = prob::load_layout(std::string(CUEPLAN_PROBLEMS_DIR) + "/runs/" + stem + ".yaml");
    ASSERT_TRUE(r.ok()) << r.error;
    ASSERT_TRUE(r.layout->game.has_value()) << stem;
    EXPECT_EQ(prob::check_game_balls(r.layout->problem.scene.balls, *r.layout->game), "") << stem;
  }
}

}  // namespace
