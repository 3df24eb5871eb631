// PropertyList: copies share their entries until one changes (copy on write), and a copy that
// changes one entry's value (a template's copy placed: SetValue) holds that entry alone.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lang/scene.h"

namespace prs::lang {
namespace {

std::vector<std::string> Texts(const PropertyList& list) {
  std::vector<std::string> texts;
  for (const auto& [name, value] : list) texts.push_back(name + "=" + Repr(value));
  return texts;
}

PropertyList Template() {
  return PropertyList{{"position", Value(1.0)}, {"width", Value(2.0)}, {"color", Value(3.0)}};
}

TEST(PropertyListTest, ACopySetsOneValueAndLeavesTheOriginalAsItWas) {
  const PropertyList original = Template();
  PropertyList copy = original;
  copy.SetValue(0, Value(7.0));
  EXPECT_EQ(Texts(original), (std::vector<std::string>{"position=1", "width=2", "color=3"}));
  EXPECT_EQ(Texts(copy), (std::vector<std::string>{"position=7", "width=2", "color=3"}));
  EXPECT_EQ(Repr(copy[0].second), "7");
  EXPECT_EQ(copy[0].first, "position");
  EXPECT_EQ(copy.size(), 3u);

  copy.SetValue(0, Value(8.0));  // the same entry again
  copy.SetValue(2, Value(9.0));  // another entry: the list is copied
  EXPECT_EQ(Texts(copy), (std::vector<std::string>{"position=8", "width=2", "color=9"}));
  EXPECT_EQ(Texts(original), (std::vector<std::string>{"position=1", "width=2", "color=3"}));

  PropertyList copy_of_copy = copy;  // shares the copy's entries, then writes them
  copy_of_copy.Mutable()[1].second = Value(5.0);
  EXPECT_EQ(Texts(copy), (std::vector<std::string>{"position=8", "width=2", "color=9"}));
  EXPECT_EQ(Texts(copy_of_copy), (std::vector<std::string>{"position=8", "width=5", "color=9"}));
}

TEST(PropertyListTest, WritingEveryEntryKeepsTheValueSetAlone) {
  const PropertyList original = Template();
  PropertyList copy = original;
  copy.SetValue(1, Value(4.0));
  const PropertyList copy_before = copy;  // shares the entries and holds the same value
  std::vector<PropertyList::Entry>& entries = copy.Mutable();
  EXPECT_EQ(Repr(entries[1].second), "4");
  entries[2].second = Value(6.0);
  EXPECT_EQ(Texts(copy), (std::vector<std::string>{"position=1", "width=4", "color=6"}));
  EXPECT_EQ(Texts(copy_before), (std::vector<std::string>{"position=1", "width=4", "color=3"}));
  EXPECT_EQ(Texts(original), (std::vector<std::string>{"position=1", "width=2", "color=3"}));
}

TEST(PropertyListTest, AListOfItsOwnIsWrittenInPlace) {
  PropertyList list = Template();
  list.SetValue(0, Value(5.0));
  PropertyList copy = list;  // after the write: sees it
  EXPECT_EQ(Texts(copy), (std::vector<std::string>{"position=5", "width=2", "color=3"}));
  list.SetValue(0, Value(6.0));  // now shared: this list's own entry, the copy unchanged
  EXPECT_EQ(Texts(list), (std::vector<std::string>{"position=6", "width=2", "color=3"}));
  EXPECT_EQ(Texts(copy), (std::vector<std::string>{"position=5", "width=2", "color=3"}));
}

}  // namespace
}  // namespace prs::lang
