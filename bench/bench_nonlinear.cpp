// placeholder: being written (issue 3, nonlinear model)
