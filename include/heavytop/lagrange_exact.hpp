#pragma once
// placeholder: being written (issue 6)
