//! Step events as data (flow/step_event.h): their names, as metrics.csv joins them.
#include "sdflow/flow/step_event.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace sdflow {
namespace {

constexpr StepEventKind kAllKinds[] = {StepEventKind::start,   StepEventKind::rejected, StepEventKind::fallback,
                                       StepEventKind::remeshed, StepEventKind::surgery, StepEventKind::split,
                                       StepEventKind::merged,  StepEventKind::cleaned, StepEventKind::refused,
                                       StepEventKind::touchdown, StepEventKind::contact};

TEST(StepEvent, every_kind_has_its_own_name_without_the_separator)
{
  std::set<std::string> names;
  for (const StepEventKind kind : kAllKinds) {
    const std::string name(event_name(kind));
    EXPECT_NE(name, "unknown");
    EXPECT_EQ(name.find('+'), std::string::npos) << name;
    names.insert(name);
  }
  EXPECT_EQ(names.size(), std::size(kAllKinds));
}

TEST(StepEvent, names_are_joined_in_order_and_found_by_kind)
{
  const std::vector<StepEvent> events = {{.kind = StepEventKind::start},
                                         {.kind = StepEventKind::rejected, .rejections = 2},
                                         {.kind = StepEventKind::surgery},
                                         {.kind = StepEventKind::split}};
  EXPECT_EQ(event_names(events), "start+rejected+surgery+split");
  EXPECT_EQ(event_names({}), "");
  EXPECT_TRUE(has_event(events, StepEventKind::split));
  EXPECT_FALSE(has_event(events, StepEventKind::merged));
}

} // namespace
} // namespace sdflow
