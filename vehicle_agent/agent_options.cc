#include "vehicle_agent/agent_options.h"
