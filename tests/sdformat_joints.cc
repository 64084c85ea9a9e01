// Loads a URDF with Gazebo's parser (libsdformat) as Gazebo would, and prints what
// the model kept: links, joints by type, and the total mass. Used by hexaleg's tests.
#include <iostream>
#include <map>
#include <sdf/sdf.hh>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: sdformat_joints FILE.urdf" << std::endl;
    return 2;
  }
  sdf::Root root;
  sdf::Errors errors = root.Load(argv[1]);
  for (const auto& error : errors) std::cerr << "sdformat: " << error.Message() << std::endl;
  const sdf::Model* model = root.Model();
  if (model == nullptr) {
    std::cerr << "sdformat: no model" << std::endl;
    return 1;
  }
  std::map<std::string, int> types;
  for (uint64_t i = 0; i < model->JointCount(); ++i) {
    const sdf::Joint* joint = model->JointByIndex(i);
    types[joint->Type() == sdf::JointType::REVOLUTE ? "revolute" : "other"] += 1;
  }
  double mass = 0.0;
  for (uint64_t i = 0; i < model->LinkCount(); ++i) mass += model->LinkByIndex(i)->Inertial().MassMatrix().Mass();
  std::cout << "links " << model->LinkCount() << "\n";
  std::cout << "revolute " << types["revolute"] << "\n";
  std::cout << "other " << types["other"] << "\n";
  std::cout.precision(17);
  std::cout << "mass " << mass << "\n";
  std::cout << "frames " << model->FrameCount() << "\n";
  return 0;
}
