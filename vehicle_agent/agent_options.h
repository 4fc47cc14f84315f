// Placeholder so the library is never empty while its parts land; replaced by the agent's
// options aggregate once the pipeline exists.
#pragma once
