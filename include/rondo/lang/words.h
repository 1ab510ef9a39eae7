// Word-level helpers of the command language (docs/commands.md): how names and phrases are
// normalised before they are compared, identifiers made from words, and the nearest known names
// offered when a phrase matches none.
//
//   normalise_phrase("The Librarian's desk in Room A-110")  ->  "librarian's desk in a-110"
//   slug("red letter")                                       ->  "red-letter"
//   nearest("a-121", {"a-111", "a-120", "kitchen"}, 2)       ->  {"a-120", "a-111"}
//
// Matching is exact after normalisation; edit distance only ranks suggestions, it never picks a
// place.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rondo::lang {

// Lower case (ASCII), typographic apostrophes as ', runs of spaces as one, surrounding
// punctuation off each word, and the filler words "the", "a", "an", "room", "office" left out.
// A name made only of filler words (a node called "Office") keeps them, lower-cased.
std::string normalise_phrase(std::string_view text);

// An object as people describe it: folded like normalise_phrase() but only leading articles are
// left out ("The Office Chair" -> "office chair"). Deliveries and their cancellations compare
// objects in this form.
std::string normalise_object(std::string_view text);

// Lower-case letters and digits, every other run of characters one '-', none at the ends:
// "Exit-West" -> "exit-west", "red letter" -> "red-letter". Empty text gives "x".
std::string slug(std::string_view text);

// Levenshtein distance over bytes, capped at `cap` (work is O(|a|·|b|); inputs are short).
std::size_t edit_distance(std::string_view a, std::string_view b, std::size_t cap = 1000);

// The `count` candidates closest to `word`: those sharing more of its words (split at spaces and
// '-': "desk in a-123" shares three with "a-123-desk") first, then by edit distance, then the one
// sharing a longer prefix with `word`, then the candidates' order.
std::vector<std::string> nearest(std::string_view word, const std::vector<std::string>& candidates, std::size_t count);

}  // namespace rondo::lang
