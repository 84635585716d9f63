#pragma once
/// @file
/// What mjarm's pages (the replay and live page, the sweep dashboard) share around their script:
/// the document's head, and text made safe for HTML and for a JSON block inside a script element.

#include <string>

namespace mjarm {

/// @p text with & < > " escaped, for an element's text or an attribute.
std::string html_text(const std::string& text);

/// JSON for a `<script type="application/json">` block: a '<' (only ever inside a string) is
/// written \u003c, so that it cannot close the element.
std::string script_safe_json(const std::string& json);

/// The page up to its `<body>`: doctype, charset, viewport, @p title, then @p head (markup of the
/// head's own, as is).
std::string html_page_head(const std::string& title, const std::string& head = {});

}  // namespace mjarm
