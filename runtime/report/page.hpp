// The page around a report's sections: inline style, a Content-Security-Policy that lets the
// page load nothing but data: images and its own inline style and script, and a small script
// that, on load, checks every picture decoded and writes the result into the page
// (#sgnlf-image-check, data-images="loaded/total"; a console error per picture that did not).
#pragma once
#include <string>

namespace sgnlf::report {

std::string html_page(const std::string& title, const std::string& body);

}  // namespace sgnlf::report
