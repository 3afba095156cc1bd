#include "layout_runner.hpp"
#include "runner.hpp"

namespace penumbra::vulkan {

std::string run_layout(const Context& context, const LayoutInputs& inputs, LayoutOutput& output) {
    try {
        detail::Runner runner(context, inputs);
        runner.run(output);
        return {};
    } catch (const detail::Failure& f) {
        return f.message;
    } catch (const nlohmann::json::exception& e) {
        return std::string("layout.json: ") + e.what();
    }
}

} // namespace penumbra::vulkan
